// btflut render: the GL renderer, headless (OSMesa or EGL).
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/scene_renderer.h"

namespace btflut::cli {

namespace {

struct RenderOptions {
    std::string input;
    std::string size;
    std::string mode;
    std::string interpolation;
    bool stats = false;
    bool quiet = false;
    bool json = false;
    std::string light;
    std::string view;
    std::string output;
    std::string backend = "auto";
    bool native = false;
    bool verbose = false;
    int depth = 8;
    bool noDither = false;
};

// What was written, as --json prints it (a scene's statistics with it; --native's: where the
// light fell, `light`).
void printWritten(const RenderOptions& o, const Image& image, const RenderStats* stats,
                  const nlohmann::json& light = nullptr) {
    if (o.json) {
        nlohmann::json out{{"output", o.output}, {"width", image.width}, {"height", image.height}};
        if (!light.is_null()) out.update(light);
        if (stats) {
            const RenderStats& s = *stats;
            out["stats"] = {{"materials_loaded", s.loadedMaterials},
                            {"materials_skipped", s.skippedMaterials},
                            {"ptms_loaded", s.loadedPtms},
                            {"images_loaded", s.imagesLoaded},
                            {"view_layers", s.viewLayers},
                            {"view_layers_loaded", s.viewLayersLoaded},
                            {"quads_drawn", s.quadsDrawn},
                            {"quads_unlit", s.quadsUnlit},
                            {"quads_culled", s.quadsCulled},
                            {"relit_textures", s.relitTextures},
                            {"relight_passes", s.relightPasses},
                            {"relit_texels", s.relitTexels},
                            {"quads_texture_space", s.quadsTextureSpace},
                            {"quads_per_fragment", s.quadsPerFragment},
                            {"texture_bytes",
                             {{"total", s.textureBytes.total()},
                              {"references", s.textureBytes.reference},
                              {"blended_references", s.textureBytes.prediction},
                              {"relit", s.textureBytes.relit},
                              {"luts", s.textureBytes.luts},
                              {"ptms", s.textureBytes.ptm},
                              {"images", s.textureBytes.images}}}};
        }
        std::cout << jsonText(out);
    } else if (!o.quiet) {
        std::cout << "wrote " << o.output << " (" << image.width << "x" << image.height << ")\n";
    }
}

Result<std::unique_ptr<HeadlessContext>> makeContext(const RenderOptions& o) {
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (context && o.verbose) (o.json ? std::cerr : std::cout) << "context: " << (*context)->description() << "\n";
    return context;
}

// SCENE.json, with --size, --light and --mode overriding the file.
Status runSceneRender(const RenderOptions& o) {
    Result<Scene> scene = loadScene(o.input);
    if (!scene) return Error{scene.error()};
    if (!o.size.empty()) {
        Result<FrameSize> size = parseFrameSize(o.size);
        if (!size) return Error{size.error()};
        scene->width = size->width;
        scene->height = size->height;
    }
    if (!o.light.empty()) {
        Result<Direction> light = parseDirection(o.light, "--light");
        if (!light) return Error{light.error()};
        scene->light = toVector(*light);
    }
    if (!o.mode.empty()) {
        Result<RenderMode> mode = parseRenderMode(o.mode);
        if (!mode) return Error{"--" + mode.error()};
        for (SceneQuad& q : scene->quads) q.mode = *mode;
    }
    if (!o.interpolation.empty()) {
        scene->interpolateLuts = o.interpolation != "nearest";
        scene->exactMatch = o.interpolation == "exact";
    }
    if (o.noDither) scene->dither = false;
    Result<std::unique_ptr<HeadlessContext>> context = makeContext(o);
    if (!context) return Error{context.error()};
    RenderStats stats;
    Result<Image> image = renderScene(*scene, stats);
    if (!image) return Error{image.error()};
    if (Status s = savePng(*image, o.output, o.depth); !s) return s;
    if (o.stats && !o.json) {
        auto list = [](const std::vector<std::string>& names) {
            std::string s;
            for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
            return s.empty() ? std::string("none") : s;
        };
        std::cout << "materials loaded: " << list(stats.loadedMaterials)
                  << "\nmaterials skipped (no visible quad uses them): " << list(stats.skippedMaterials)
                  << "\nquads drawn: " << stats.quadsDrawn << " (" << stats.quadsUnlit
                  << " unlit), culled: " << stats.quadsCulled
                  << "\nPTMs loaded (for ptm quads): " << list(stats.loadedPtms)
                  << "\nmeasured images loaded (for nearest quads): " << stats.imagesLoaded
                  << "\nview layers decoded: " << stats.viewLayersLoaded << " of " << stats.viewLayers
                  << "\nrelit textures (mode lut, one per material and light direction): " << stats.relitTextures
                  << ", made by " << stats.relightPasses << " relight passes of " << stats.relitTexels
                  << " texels (a quad minified 2^m times relit from mip level m alone)"
                  << "\nmode lut, banks relit whole (one view layer, or a predictor of views): "
                  << stats.quadsTextureSpace << " quads drawn from relit textures, " << stats.quadsPerFragment
                  << " relit per fragment (the light moved and that cost less)"
                  << "\ntexture memory: " << stats.textureBytes.total() << " bytes (references "
                  << stats.textureBytes.reference << ", blended references " << stats.textureBytes.prediction
                  << ", relit " << stats.textureBytes.relit << ", LUTs " << stats.textureBytes.luts << ", PTMs "
                  << stats.textureBytes.ptm << ", measured images " << stats.textureBytes.images << ")\n";
    }
    printWritten(o, *image, &stats);
    return success();
}

Status runRender(const RenderOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    if (!o.mode.empty())
        if (Result<RenderMode> mode = parseRenderMode(o.mode); !mode) return Error{"--" + mode.error()};
    if (fileExtension(o.input) == "json") {
        if (o.native) return Error{"--native renders a bank (M.btflut), not a scene"};
        if (!o.view.empty()) return Error{"--view applies to --native; a scene's camera sets the view"};
        return runSceneRender(o);
    }
    if (!o.native)
        return Error{
            "a bank (M.btflut) renders with --native: the frontal quad at its reference image's "
            "resolution; scenes are SCENE.json"};
    // Options of scenes that --native cannot honour are refused, never ignored.
    if (!o.mode.empty() && o.mode != "lut")
        return Error{"--native draws the lut mode (relight's twin); --mode " + o.mode + " needs a scene (SCENE.json)"};
    if (!o.size.empty()) return Error{"--native renders at the reference image's own size; --size is for scenes"};
    if (o.stats) return Error{"--stats reports on scenes (SCENE.json), not --native"};
    if (o.light.empty()) return Error{"--native needs --light THETA,PHI"};
    Result<BankAtDirection> query = loadBankAt(o.input, o.light, o.view);
    if (!query) return Error{query.error()};
    LutBank& bank = query->bank;
    Result<std::unique_ptr<HeadlessContext>> context = makeContext(o);
    if (!context) return Error{context.error()};
    Result<Image> image = renderNative(bank, query->light, query->view, !o.noDither, o.interpolation != "nearest");
    if (!image) return Error{o.input + ": " + image.error()};
    if (Status s = savePng(*image, o.output, o.depth); !s) return s;
    // Where the light fell, as relight --json says it: the LUT's source and the provenances.
    const BankLookup at = bank.lookup(query->light, query->view);
    printWritten(o, *image, nullptr,
                 {{"light", {{"theta", query->light.theta * 180 / M_PI}, {"phi", query->light.phi * 180 / M_PI}}},
                  {"lut", provenanceName(at.provenance)},
                  {"light_provenance", provenanceName(at.lightProvenance)},
                  {"view_provenance", provenanceName(at.viewProvenance)}});
    return success();
}

}  // namespace

void addRenderCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* app =
        root.add_subcommand("render",
                            "Render with OpenGL, headless (OSMesa or EGL): a scene (SCENE.json, docs/scene.md) or, "
                            "with --native, a bank's reference at its own resolution");
    app->add_option("INPUT", o->input, "SCENE.json or M.btflut")->required();
    app->add_option("--light", o->light,
                    "light THETA,PHI in degrees (bank: its sample frame; scene: the world, z up; "
                    "overrides the file)");
    app->add_option("--size", o->size, "scene image size WxH (overrides the file)");
    app->add_option("--mode", o->mode,
                    "lut, brdf, ptm, flat or nearest for every quad (overrides the file); --native draws lut only");
    app->add_option("--interpolation", o->interpolation,
                    "linear: LUTs interpolated between the measured directions (banks with a predictor: "
                    "their match LUTs read from the baked grid); exact: banks with a predictor make the LUT at "
                    "the light, as relight (and --native) do; nearest: the nearest one's (overrides the file)")
        ->check(CLI::IsMember({"linear", "exact", "nearest"}));
    app->add_flag("--stats", o->stats, "print what was loaded, what was skipped and the texture memory");
    app->add_option("--view", o->view,
                    "with --native: view direction THETA,PHI in degrees (default: the reference image's view)");
    app->add_flag("--native", o->native, "the frontal quad at the reference image's own resolution");
    app->add_option("-o,--output", o->output, "out.png")->required();
    app->add_option("--backend", o->backend, "auto (EGL, then OSMesa), osmesa or egl")->capture_default_str();
    app->add_flag("-v,--verbose", o->verbose, "print the context's backend and driver");
    addLutImageOptions(*app, o->depth, o->noDither);
    addQuietFlag(*app, o->quiet);
    app->add_flag("--json", o->json, "print what was written as JSON (a scene's: with the statistics of --stats)");
    commands.push_back({app, [o] { return runRender(*o); }});
}

}  // namespace btflut::cli
