#pragma once
// The fitted rough-surface model as an estimate of the targets between measured lights
// (issue 34): the model (fit.h) is fitted to the measured nodes' histograms, its distribution
// over each layer's measured reach is put in the nodes' form (quantile functions, or LUTs
// from the reference), and that smooth function of the light is fitted by a polynomial
// (target_fit.h; in the isotropic domain, of the pair's point). A lookup then adds the model's change between the
// measured lights as it adds any fit's (fit(L) - sum_n w_n fit(L_n)): the measurements keep their levels, which the
// model may get wrong (albedo, background), and the model supplies how the distribution moves between them (shadows
// growing towards the horizon). One candidate of the choice (bake/target_choice.h), alone or mixed with a polynomial
// fitted to the measurements.
//
//   NodeForm form{.quantiles = 1024};      // or {.entries = 256, .reference = massPerEntry}
//   Result<ModelTargets> model = modelTargetFits(bank, form);   // a fit per layer

#include "core/bank/lut_bank.h"
#include "core/physics/surface.h"

namespace btflut {

/// What a bank's node values are: quantile functions of `quantiles` samples, or (quantiles 0)
/// LUTs of `entries` entries from a reference whose share of texels per entry is `reference`.
struct NodeForm {
    int quantiles = 0;
    int entries = 256;
    std::vector<double> reference;
};

struct ModelTargets {
    std::vector<TargetFit> layers;  ///< per layer of the bank (layers domain)
    TargetFit pairs;                ///< over the pairs' points (isotropic domain)
    SurfaceModel model;             ///< the fitted model
    double rms = 0;                 ///< the fit's residual over every histogram bin
};

/// The model fitted (Lambertian) to the 64-bin histograms of the bank's measured nodes (at
/// most kModelFitNodes of them, evenly spread over the layers; the same histograms fitted
/// again are answered from memory), then each layer's fit, or in the isotropic domain one fit
/// over the pairs' points, sampled over the box the measured points span. The bank's node values must be one
/// channel of one region. Errors: another form, a fit that fails (too few lights, no
/// convergence), distributions that are not finite.
constexpr std::size_t kModelFitNodes = 16;
Result<ModelTargets> modelTargetFits(const LutBank& bank, const NodeForm& form);

}  // namespace btflut
