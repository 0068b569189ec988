#include "cli/model_options.h"

namespace btflut::cli {

void addModelOptions(CLI::App& app, ModelFlags& f, bool roughnessRequired) {
    auto* r = app.add_option("--roughness", f.roughness, "rms slope r of the Gaussian surface (> 0)");
    if (roughnessRequired) r->required();
    app.add_option("--brdf", f.brdf, "local BRDF: lambert, ts (Torrance-Sparrow) or mix (kd lambert + ks ts)")
        ->check(CLI::IsMember({"lambert", "ts", "mix"}))
        ->capture_default_str();
    app.add_option("--sigma", f.sigma, "Torrance-Sparrow facet slope width (> 0)")->capture_default_str();
    app.add_option("--kd", f.kd, "diffuse weight (lambert: default 1; mix: required)");
    app.add_option("--ks", f.ks, "specular weight (ts: default 1; mix: required)");
    app.add_option("--ior", f.ior, "index of refraction for Fresnel (>= 1)")->capture_default_str();
    app.add_option("--gain", f.gain, "camera gain; values clip at 1 (> 0)")->capture_default_str();
}

Result<SurfaceModel> modelFromFlags(const ModelFlags& f) {
    return makeSurfaceModel(f.roughness, f.brdf, f.kd, f.ks, f.sigma, f.ior, f.gain, "--");
}

}  // namespace btflut::cli
