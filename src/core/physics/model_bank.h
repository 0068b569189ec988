#pragma once
// LUT banks from the rough-surface model, for a material that has a reference image but no
// measurements under other lights (paper section 6: "one could estimate material
// parameters ... and use a model").
//
//   Result<ModelBankParams> p = parseModelParams(text, "concrete.json");   // docs/model-params.md
//   Result<LutBank> bank = bakeModelBank(*p, reference, mask, {...});
//
// Each LUT gives the reference's grey values the model's histogram at one light direction
// (for the file's view direction).

#include <vector>

#include "core/bank/lut_bank.h"
#include "core/physics/simulate.h"

namespace btflut {

struct ModelBankParams {
    SurfaceModel model;
    SimulationOptions simulation{.method = SimulationMethod::Quadrature, .bins = 1024, .nodes = 48};
    Direction view;                 ///< the camera; default frontal
    std::vector<Direction> lights;  ///< default: the pole and rings every 10 degrees to 80, every 30 in azimuth
};

/// Parses a model parameters file (JSON); errors name the file and the field.
Result<ModelBankParams> parseModelParams(const std::string& text, const std::string& file);

/// The same from a file (bake --model, --fill model --params, a library of materials).
Result<ModelBankParams> loadModelParams(const std::string& path);

/// The model part of a parameters file (brdf, roughness, kd, ks, sigma, ior, gain, smooth),
/// as JSON text that parseModelParams reads back.
std::string modelParamsText(const ModelBankParams& params);

struct ModelReference {
    std::string name;
    Direction light;  ///< the light the reference image was taken under
    int gridSize = 17;
    int entries = 0;  ///< 0: 256 for an 8-bit reference, 1024 for a 16-bit one
};

/// The bank: grey LUTs from the reference's grey distribution over `mask` to the model's
/// histogram at every light of `params`.
Result<LutBank> bakeModelBank(const ModelBankParams& params, const Image& reference, const Mask& mask,
                              const ModelReference& about);

}  // namespace btflut
