#pragma once
// A material's grey-level histogram at any light and view direction (sample frame), from a
// fitted model (btflut fit's PARAMS.json) or a LUT bank: what the paper's inverse problems
// compare one image's histogram with (orientation, section 6.4; recognition, section 6.3).
//
//   Result<MaterialHistograms> m = loadMaterial("concrete.json");    // or "concrete.btflut"
//   std::vector<double> h = m->at(light, view, 64);

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/physics/model_bank.h"

namespace btflut {

struct MaterialHistograms {
    std::string name;  ///< the file's stem
    std::string path;
    std::optional<ModelBankParams> model;  ///< a fitted model, or
    std::shared_ptr<const LutBank> bank;   ///< a bank (its reference through its LUTs)
    LevelCounts referenceGrey;             ///< bank: the reference's grey over its sample
    std::vector<double> regionShares;      ///< bank making LUTs: each region's share of the sample

    /// The normalised `bins`-bin histogram at a light and view (sample frame). The model
    /// integrates with `nodes` quadrature nodes (simulate.h); a bank interpolates its LUTs
    /// (clamped, or modelled, beyond its measurements).
    std::vector<double> at(Direction light, Direction view, int bins, int nodes = 24) const;
};

/// A model parameters file (.json) or a bank (.btflut); errors name the file. Banks must
/// hold their reference and grey LUTs (grey or lrgb).
Result<MaterialHistograms> loadMaterial(const std::string& path);

}  // namespace btflut
