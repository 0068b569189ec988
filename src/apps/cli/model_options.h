#pragma once
// Command-line flags of the rough-surface model, shared by `simulate` and `bench simulate`
// (and, later, `synth`): --roughness, --brdf, --sigma, --kd, --ks, --ior, --gain.

#include <optional>

#include "cli/command.h"

#include "core/physics/surface.h"

namespace btflut::cli {

struct ModelFlags {
    double roughness = 0.4;
    std::string brdf = "lambert";
    double sigma = 0.13;
    std::optional<double> kd, ks;
    double ior = 1.5;
    double gain = 1;
};

void addModelOptions(CLI::App& app, ModelFlags& flags, bool roughnessRequired);

/// The model the flags describe: lambert uses kd (default 1), ts uses ks (default 1), mix
/// needs both. Refuses invalid values with the flag's name.
Result<SurfaceModel> modelFromFlags(const ModelFlags& flags);

}  // namespace btflut::cli
