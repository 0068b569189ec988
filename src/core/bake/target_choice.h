#pragma once
// How a bank estimates its target between measured lights, chosen by validation on the
// measured lights themselves (issue 34): the blend of the measured quantile functions (or of a
// bank of LUTs' LUTs) alone, or the blend corrected by a polynomial fit over the light
// (bank/target_fit.h) of degree 1 to 5 with one of four ridge weights, by the fitted
// rough-surface model's change over the light (inverse/model_target.h; where the nodes hold one
// grey distribution in one region), or by the model and each polynomial half and half. Per
// layer, the measured lights are left out in turn (each once: up to 8 folds, every 8th light
// a fold), each candidate estimates them from the others through the bank's own lookup, and
// each region is scored by the 64-bin histogram L1 of the estimate against the measured
// distribution. Per region the rule takes the fit of the lowest mean among those that beat the
// blend by more than two standard errors of the per-light differences, and only fits with two
// of a fold's lights per coefficient are tried: few or badly spread lights keep the blend. A
// layer of fewer than kMinFitLights measured lights keeps the blend unvalidated. A bank in the
// isotropic domain makes one such choice over all its points (light and view pairs), the
// polynomials in the point's coordinates, every eighth point left out in turn.
//
//   chooseTargetFits(bank, threads);   // sets each layer's fit (or bank.pairFit) and bank.targetChoice

#include "core/bank/lut_bank.h"

namespace btflut {

/// A layer needs this many measured lights for its targets to be fitted and validated.
constexpr std::size_t kMinFitLights = 6;

/// Chooses and fits each layer's estimate (ViewLayer::fit) of a bank:
/// one that makes its LUTs against measured targets (its quantile functions), or a bank of
/// LUTs (its LUTs: each a quantile function read at the reference's levels, so the same fit
/// applies, scored with each entry weighed by `entryWeights[channel][entry]`, the reference's
/// share of texels there); in the isotropic domain, the bank's one estimate over its pairs
/// (LutBank::pairFit). Records the candidates' figures in bank.targetChoice. Leaves other banks
/// (correction targets, model-filled isotropic nodes) as they are. The grids are not refilled (the caller's).
void chooseTargetFits(LutBank& bank, int threads, const std::vector<std::vector<double>>& entryWeights = {});

/// In words, what bank.targetChoice chose: "blend" or a fit's name ("poly3 ridge 0.0001");
/// where regions differ, each region's ("per region: poly1 ridge 0.0001, blend"), and where
/// layers differ, each choice with its count ("poly2 ridge 0.001 x3, blend x1"); "blend" for
/// a bank without the choice.
std::string targetChoiceSummary(const LutBank& bank);

}  // namespace btflut
