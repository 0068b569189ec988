#pragma once
// Directions without measurements, filled from the fitted rough-surface model (paper
// section 6.5, last paragraph) instead of clamped to the measured boundary.
//
//   Result<ModelBankParams> params = ...;                 // btflut fit's output
//   Result<ModelFillReport> r = fillFromModel(bank, *params, modelParamsText(*params));
//
// In every view layer, the grid nodes inside the light disk that the measured lights do not
// enclose, their neighbours, and a ring of directions at the horizon become nodes of the bank
// marked `modelled`. A modelled node at light l takes the measurements where l leaves their
// hull (at the nearest point of the hull, b) and carries them on with the model's change from
// b to l: its LUT is T o LUT(b), T the transport (matching LUT) from the model's histogram at
// b to the model's at l. So the measurements keep their absolute levels, which the model may
// get wrong (albedo, background, interreflection), and the model supplies only the trend;
// inside the hull T is the identity. Lookups inside the measured hull use the measurements
// alone; beyond it they move from the measurements clamped to the hull to the modelled nodes
// over one grid step, and say "modelled".

#include <optional>

#include "core/bank/lut_bank.h"
#include "core/inverse/fit.h"
#include "core/physics/model_bank.h"

namespace btflut {

struct ModelFillReport {
    std::size_t nodes = 0;          ///< modelled nodes added over every layer
    std::optional<SurfaceFit> fit;  ///< fillFromDataset without parameters: the fit
};

/// Fills `bank` (domain layers; grey, or blending references in one region) from the model,
/// then rebuilds its triangulations and grids. `description` (the model's parameters as
/// JSON) is kept in the bank. Errors: a domain or colour the model cannot fill, a bank that
/// already has modelled nodes.
Result<ModelFillReport> fillFromModel(LutBank& bank, const ModelBankParams& params, const std::string& description);

/// fillFromModel for a bank baked from `dataset`: with `params` null, the model is first
/// fitted (`brdf`) to the dataset's 64-bin masked grey histograms (kFillHistogramBins): those
/// given in `histograms` (one row per image, as a bake collected them while decoding), or,
/// without, decoded again from the files.
constexpr int kFillHistogramBins = 64;  // the paper's
Result<ModelFillReport> fillFromDataset(LutBank& bank, const Dataset& dataset, const ModelBankParams* params,
                                        FitBrdf brdf = FitBrdf::Lambert,
                                        const std::vector<HistogramRow>* histograms = nullptr);

}  // namespace btflut
