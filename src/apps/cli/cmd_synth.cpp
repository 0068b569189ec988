// btflut synth: image sets of Gaussian rough surfaces with known truth.
#include <iostream>
#include <memory>

#include "cli/command.h"
#include "cli/model_options.h"
#include "core/synth/synth.h"

namespace btflut::cli {

namespace {

struct SynthOptions {
    std::string preset = "concrete";
    ModelFlags model;
    double roughnessAcross = 0;
    double angle = 0;
    double correlationLength = 16;
    double albedoVariation = 0, ambient = 0, noise = 0;
    std::string geometry = "curet-c2";
    int size = 512;
    int samples = 2;
    std::uint64_t seed = 1;
    int depth = 8;
    bool force = false;
    bool quiet = false;
    int threads = 0;
    std::string output;
};

Status runSynth(const SynthOptions& o, const CLI::App& app) {
    Result<SynthMaterial> material = synthPreset(o.preset);
    if (!material) return Error{material.error()};
    auto given = [&](const char* flag) { return app.get_option(flag)->count() > 0; };
    SynthMaterial& m = *material;
    // Flags given explicitly override the preset.
    if (given("--roughness")) m.surface.roughness = o.model.roughness;
    if (given("--roughness-across")) m.surface.roughnessAcross = o.roughnessAcross;
    if (given("--angle")) m.surface.angle = o.angle * kDegree;
    m.surface.correlationLength = o.correlationLength;
    m.surface.size = o.size;
    m.surface.seed = o.seed;
    const bool lambert = m.model.brdf.ks == 0, ts = m.model.brdf.kd == 0;
    const std::string brdf = given("--brdf") ? o.model.brdf : lambert ? "lambert" : ts ? "ts" : "mix";
    Result<SurfaceModel> model = makeSurfaceModel(
        m.surface.roughness, brdf, given("--kd") ? o.model.kd : std::optional(m.model.brdf.kd),
        given("--ks") ? o.model.ks : std::optional(m.model.brdf.ks),
        given("--sigma") ? o.model.sigma : m.model.brdf.sigma, given("--ior") ? o.model.ior : m.model.brdf.ior,
        given("--gain") ? o.model.gain : m.model.gain, "--");
    if (!model) return Error{model.error()};
    m.model = *model;
    m.albedoVariation = o.albedoVariation;
    m.ambient = o.ambient;
    m.noise = o.noise;
    Result<std::vector<Geometry>> geometry = parseGeometry(o.geometry);
    if (!geometry) return Error{geometry.error()};
    SynthOutput out{.samplesPerAxis = o.samples, .bitDepth = o.depth, .force = o.force, .threads = o.threads};
    if (!o.quiet) out.progress = terminalProgress("rendering");
    if (Status s = writeSynthDataset(m, *geometry, o.output, out); !s) return s;
    if (!o.quiet)
        std::cout << "wrote " << o.output << ": " << geometry->size() << " images of " << o.size << "x" << o.size
                  << ", " << o.preset << " (r " << m.surface.roughness << "), manifest btflut-dataset.json\n";
    return success();
}

}  // namespace

void addSynthCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<SynthOptions>();
    CLI::App* app =
        root.add_subcommand("synth", "Render image sets of Gaussian rough surfaces (known truth) as a dataset folder");
    app->add_option("-o,--output", o->output, "output folder (PNGs, mask.png, btflut-dataset.json, synth.lp)")
        ->required();
    app->add_option("--preset", o->preset, "concrete, foil, plastic or corduroy; flags override it")
        ->capture_default_str();
    addModelOptions(*app, o->model, false);
    app->add_option("--roughness-across", o->roughnessAcross, "rms slope across the principal axis (anisotropy)");
    app->add_option("--angle", o->angle, "principal axis, degrees from x towards y");
    app->add_option("--correlation-length", o->correlationLength, "pixels (4 .. size/4)")->capture_default_str();
    app->add_option("--albedo-variation", o->albedoVariation, "0..1: smooth random albedo 1 - v u")
        ->capture_default_str();
    app->add_option("--ambient", o->ambient, "constant diffuse irradiance (interreflection)")->capture_default_str();
    app->add_option("--noise", o->noise, "sensor noise standard deviation")->capture_default_str();
    app->add_option("--geometry", o->geometry,
                    "curet-c2, curet-specular, rti-N (N lights, frontal camera), btf-N (N views x N lights, rendered "
                    "rectified), a list or a dataset")
        ->capture_default_str();
    app->add_option("--size", o->size, "field and image size in pixels (any size FFTW takes)")->capture_default_str();
    app->add_option("--samples", o->samples, "rays per pixel along each axis")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    app->add_option("--seed", o->seed, "surface seed")->capture_default_str();
    app->add_option("--depth", o->depth, "bits per sample")->check(CLI::IsMember({8, 16}))->capture_default_str();
    app->add_option("--threads", o->threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
    app->add_flag("--force", o->force, "replace an existing, non-empty output folder");
    addQuietFlag(*app, o->quiet, "no progress or summary");
    commands.push_back({app, [o, app] { return runSynth(*o, *app); }});
}

}  // namespace btflut::cli
