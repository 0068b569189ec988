// btflut bench render: frame times of the scene renderer in each mode, the light static and
// moving, wall and GPU time, interleaved; the ratios lut/flat, lut/ptm and lut/predictor, and
// texture memory per material (bench/RESULTS.md, "Renderer"). Ratios, never pass/fail.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/bench_timing.h"
#include "cli/command.h"
#include "core/bank/lut_bank.h"
#include "core/check.h"
#include "core/io/json_text.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "gl/scene_renderer.h"

namespace btflut::cli {

namespace {

struct BenchRenderOptions {
    std::string bank;
    int frames = 10;
    int repeat = 3;
    std::vector<std::string> sizes{"1024x1024", "1920x1080"};
    int overdraw = 1;
    std::string backend = "auto";
    std::string lutPath = "auto";
    bool json = false;
};

// The moving light: a new direction every frame (so no relit texture holds it), its elevation
// alternating between the two bench lights' and its azimuth sweeping between theirs.
Vec3 movingLight() {
    static int frame = 0;
    ++frame;
    return toVector(Direction::fromDegrees(frame % 2 ? 55 : 40, 252 + std::fmod(0.37 * frame, 46.0)));
}

// Frame times of one renderer: `frames` frames drawn back to back with no wait between them,
// then one glFinish (timeDraws); every quad lit.
Result<DrawTimes> timeFrames(SceneRenderer& renderer, RenderMode mode, bool moving, int frames, bool timer) {
    Result<DrawTimes> t =
        timeDraws(frames, timer, [&] { return renderer.draw(moving ? movingLight() : benchLights()[0], mode); });
    BTFLUT_CHECK(!t || renderer.stats().quadsUnlit == 0);
    return t;
}

// The headline's texture memory per material (lut against ptm, and drawn per fragment) into
// `out`, and as text.
std::string textureMemory(const SceneRenderer& renderer, nlohmann::json& out) {
    std::string text;
    char line[320];
    // Per material: lut reads the reference and draws one relit texture per light
    // direction of its quads (here four); ptm needs its three coefficient/albedo textures.
    const TextureBytes& bytes = renderer.stats().textureBytes;
    const std::size_t directions = std::max<std::size_t>(renderer.stats().relitTextures, 1);
    const std::size_t lutBytes = bytes.reference + bytes.prediction + bytes.relit + bytes.luts;
    out["texture_bytes_lut"] = lutBytes;
    out["texture_bytes_lut_per_direction"] = bytes.relit / directions;
    out["light_directions"] = directions;
    out["texture_bytes_ptm"] = bytes.ptm;
    out["lut_over_ptm_texture_bytes"] = static_cast<double>(lutBytes) / static_cast<double>(bytes.ptm);
    std::snprintf(line, sizeof line,
                  "  texture memory per material: lut %zu bytes (source %zu + %zu relit textures of %zu), ptm %zu "
                  "bytes; lut/ptm %.4f\n",
                  lutBytes, bytes.reference + bytes.prediction, directions, bytes.relit / directions, bytes.ptm,
                  static_cast<double>(lutBytes) / static_cast<double>(bytes.ptm));
    text += line;
    // Drawn per fragment a material needs its source (the reference, or a predictor's
    // planes) and a LUT per channel and region: per texel against the PTM's.
    const double texels = static_cast<double>(renderer.bank("m")->reference.pixelCount());
    const double perFragment = static_cast<double>(bytes.reference + bytes.prediction + bytes.luts) / texels;
    out["bytes_per_texel_per_fragment"] = perFragment;
    out["bytes_per_texel_ptm"] = static_cast<double>(bytes.ptm) / texels;
    std::snprintf(line, sizeof line,
                  "  drawn per fragment: %.2f bytes per texel (mipmaps and LUTs included), the PTM %.2f\n", perFragment,
                  static_cast<double>(bytes.ptm) / texels);
    text += line;
    return text;
}

// A row of bench render: a mode drawn by a renderer.
struct ModeRow {
    std::string name;
    SceneRenderer* renderer;
    RenderMode mode;
};

// Each row's frame times, by name and whether the light moves (medians taken later), and the
// last moving lut frame's stats.
struct RowTimes {
    std::map<std::pair<std::string, bool>, std::vector<double>> wall, gpu;
    RenderStats movingLutStats;
};

Result<RowTimes> timeModes(const std::vector<ModeRow>& rows, SceneRenderer& main, const BenchRenderOptions& o,
                           bool timer) {
    RowTimes times;
    for (const ModeRow& row : rows)  // the first frames load and upload
        if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return Error{s.error()};
    main.finish();
    for (int r = 0; r < o.repeat; ++r)  // interleaved, so drift hits every mode alike
        for (bool moving : {false, true})
            for (const ModeRow& row : rows) {
                if (!moving) {  // the static run starts from its light, relit before the clock starts
                    if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return Error{s.error()};
                    if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return Error{s.error()};
                    row.renderer->finish();
                }
                Result<DrawTimes> t = timeFrames(*row.renderer, row.mode, moving, o.frames, timer);
                if (!t) return Error{t.error()};
                if (moving && row.name == "lut") times.movingLutStats = row.renderer->stats();
                times.wall[{row.name, moving}].push_back(t->wall);
                times.gpu[{row.name, moving}].push_back(t->gpu);
            }
    return times;
}

// The rows' ratios (lut against flat, ptm, brdf and the predictor; static and moving; wall
// and GPU) into a size's `entry`, and as text.
std::string addRatios(nlohmann::json& entry, RowTimes& times, bool timer, bool withPredictor) {
    auto &wall = times.wall, &gpu = times.gpu;
    std::string text;
    char line[320];
    auto ratio = [&](const char* a, const char* b, bool moving, bool onGpu) {
        auto& t = onGpu ? gpu : wall;
        return median(t[{a, moving}]) / median(t[{b, moving}]);
    };
    // lut_over_flat and lut_over_ptm: the light moving every frame (as before this split).
    entry["lut_over_flat"] = ratio("lut", "flat", true, false);
    entry["lut_over_ptm"] = ratio("lut", "ptm", true, false);
    entry["lut_over_brdf"] = ratio("lut", "brdf", true, false);
    entry["lut_over_flat_static"] = ratio("lut", "flat", false, false);
    entry["lut_over_ptm_static"] = ratio("lut", "ptm", false, false);
    if (withPredictor) {
        entry["lut_over_predictor_moving"] = ratio("lut", "predictor", true, false);
        entry["lut_over_predictor_static"] = ratio("lut", "predictor", false, false);
    }
    if (timer) {
        entry["gpu_lut_over_flat"] = ratio("lut", "flat", true, true);
        entry["gpu_lut_over_ptm"] = ratio("lut", "ptm", true, true);
        entry["gpu_lut_over_flat_static"] = ratio("lut", "flat", false, true);
        entry["gpu_lut_over_ptm_static"] = ratio("lut", "ptm", false, true);
    }
    std::snprintf(line, sizeof line,
                  "    lut/flat: static %.3f, moving %.3f (GPU %.3f, %.3f);  lut/ptm: static %.3f, moving %.3f "
                  "(GPU %.3f, %.3f)\n",
                  entry["lut_over_flat_static"].get<double>(), entry["lut_over_flat"].get<double>(),
                  timer ? entry["gpu_lut_over_flat_static"].get<double>() : NAN,
                  timer ? entry["gpu_lut_over_flat"].get<double>() : NAN, entry["lut_over_ptm_static"].get<double>(),
                  entry["lut_over_ptm"].get<double>(), timer ? entry["gpu_lut_over_ptm_static"].get<double>() : NAN,
                  timer ? entry["gpu_lut_over_ptm"].get<double>() : NAN);
    text += line;
    if (withPredictor) {
        std::snprintf(
            line, sizeof line, "    lut/predictor (the predictor per fragment, no LUT): static %.3f, moving %.3f\n",
            entry["lut_over_predictor_static"].get<double>(), entry["lut_over_predictor_moving"].get<double>());
        text += line;
    }
    return text;
}

Status runBenchRender(const BenchRenderOptions& o) {
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (!context) return Error{context.error()};
    GLint timerBits = 0;
    gl.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &timerBits);
    const bool timer = timerBits > 0;
    nlohmann::json out{{"context", (*context)->description()},
                       {"bank", o.bank},
                       {"frames", o.frames},
                       {"rounds", o.repeat},
                       {"overdraw", o.overdraw},
                       {"quads", 4 * o.overdraw},
                       {"gpu_timer", timer},
                       {"sizes", nlohmann::json::array()}};
    // Static: the light stays (lut relights nothing after the first frame). Moving: a new
    // direction every frame, so each frame relights or draws per fragment (lut), recomputes
    // the brightness (brdf) or the PTM weights (ptm).
    Result<LutPath> lutPath = o.lutPath == "auto"      ? Result<LutPath>(LutPath::Auto)
                              : o.lutPath == "texture" ? Result<LutPath>(LutPath::TextureSpace)
                              : o.lutPath == "fragment"
                                  ? Result<LutPath>(LutPath::PerFragment)
                                  : Result<LutPath>(Error{"--lut-path: expected auto, texture or fragment"});
    if (!lutPath) return Error{lutPath.error()};
    std::string text;
    bool first = true;
    for (const std::string& size : o.sizes) {
        Result<FrameSize> parsed = parseFrameSize(size);
        if (!parsed) return Error{parsed.error()};
        const int w = parsed->width, h = parsed->height;
        const Scene scene = benchScene(o.bank, w, h, {}, o.overdraw);
        Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(scene, {.lutPath = *lutPath});
        if (!renderer) return Error{renderer.error()};
        // The rows: the four modes, and for a bank with a predictor the predictor drawn per
        // fragment without its LUT (what an RTI viewer draws), by a renderer of its own.
        std::vector<ModeRow> rows{{"lut", renderer->get(), RenderMode::Lut},
                                  {"flat", renderer->get(), RenderMode::Flat},
                                  {"brdf", renderer->get(), RenderMode::Brdf},
                                  {"ptm", renderer->get(), RenderMode::Ptm}};
        std::unique_ptr<SceneRenderer> predictor;
        if (const LutBank* bank = (*renderer)->bank("m"); bank && bank->makesLuts() && bank->layers.size() == 1) {
            Result<std::unique_ptr<SceneRenderer>> p =
                SceneRenderer::create(scene, {.lutPath = LutPath::PerFragment, .predictionOnly = true});
            if (!p) return Error{p.error()};
            predictor = std::move(*p);
            rows.push_back({"predictor", predictor.get(), RenderMode::Lut});
        }
        Result<RowTimes> times = timeModes(rows, *renderer->get(), o, timer);
        if (!times) return Error{times.error()};
        auto& [wall, gpu, movingLutStats] = *times;
        nlohmann::json entry{{"width", w}, {"height", h}};
        char line[320];
        std::snprintf(line, sizeof line, "  %dx%d, %d quads\n    %-9s %13s %13s %13s %13s\n", w, h, 4 * o.overdraw, "",
                      "static ms", "moving ms", "static GPU ms", "moving GPU ms");
        text += line;
        for (const ModeRow& row : rows) {
            const double sw = median(wall[{row.name, false}]), mw = median(wall[{row.name, true}]);
            const double sg = timer ? median(gpu[{row.name, false}]) : NAN,
                         mg = timer ? median(gpu[{row.name, true}]) : NAN;
            entry[row.name + "_ms"] = mw * 1e3;
            entry[row.name + "_static_ms"] = sw * 1e3;
            if (timer) {
                entry[row.name + "_gpu_ms"] = mg * 1e3;
                entry[row.name + "_static_gpu_ms"] = sg * 1e3;
            }
            std::snprintf(line, sizeof line, "    %-9s %13.2f %13.2f %13.2f %13.2f\n", row.name.c_str(), sw * 1e3,
                          mw * 1e3, sg * 1e3, mg * 1e3);
            text += line;
        }
        text += addRatios(entry, *times, timer, predictor != nullptr);
        std::snprintf(
            line, sizeof line, "    lut quads per fragment in the moving frames: %zu of %zu (the last frame)\n",
            movingLutStats.quadsPerFragment, movingLutStats.quadsPerFragment + movingLutStats.quadsTextureSpace);
        entry["lut_moving_quads_per_fragment"] = movingLutStats.quadsPerFragment;
        text += line;
        if (first) {  // the headline figures: the first size
            first = false;
            for (const char* key : {"lut_over_flat", "lut_over_ptm", "lut_over_flat_static", "lut_over_ptm_static",
                                    "lut_over_predictor_moving", "lut_over_predictor_static", "gpu_lut_over_flat",
                                    "gpu_lut_over_ptm", "gpu_lut_over_flat_static", "gpu_lut_over_ptm_static"})
                if (entry.contains(key)) out[key] = entry[key];
            text += textureMemory(**renderer, out);
        }
        out["sizes"].push_back(entry);
    }
    if (o.json) {
        std::cout << jsonText(out);
        return success();
    }
    std::cout << "render " << 4 * o.overdraw << " quads, frame times (median of " << o.repeat << " rounds of "
              << o.frames << " frames, no wait between frames), " << (*context)->description()
              << (timer ? "" : "; no GPU timer in this driver") << "\n"
              << text;
    return success();
}

}  // namespace

void addBenchRenderCommand(CLI::App& bench, Commands& commands) {
    auto ro = std::make_shared<BenchRenderOptions>();
    CLI::App* render = bench.add_subcommand(
        "render",
        "Frame times of the scene renderer in modes flat, brdf, ptm and lut (and, for a bank with a "
        "predictor, the predictor per fragment without its LUT), light static and moving (a new direction "
        "every frame), wall and GPU time, interleaved");
    render->add_option("BANK", ro->bank, "M.btflut used for every quad (baked with --ptm)")->required();
    render->add_option("--frames", ro->frames, "frames per mode and round")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    render->add_option("--repeat", ro->repeat, "rounds")->check(CLI::Range(1, 100))->capture_default_str();
    render->add_option("--size", ro->sizes, "image sizes WxH (repeatable)")->capture_default_str();
    render->add_option("--overdraw", ro->overdraw, "layers of the four quads, each drawn over the last")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    render->add_option("--backend", ro->backend, "auto, osmesa or egl")->capture_default_str();
    render
        ->add_option("--lut-path", ro->lutPath,
                     "mode lut on banks of one view layer: auto (per quad and frame, whichever costs less), texture "
                     "(relit textures only) or fragment (per fragment only)")
        ->check(CLI::IsMember({"auto", "texture", "fragment"}))
        ->capture_default_str();
    render->add_flag("--json", ro->json, "print JSON");
    commands.push_back({render, [ro] { return runBenchRender(*ro); }});
}

}  // namespace btflut::cli
