#pragma once
// `bake --predictor auto` (the default): the predictor, and how strongly to match it, chosen
// by validation on the dataset's own lights, within a byte budget per texel and a bound on its
// decoding's multiply-adds per texel.
//
//   Result<LutBank> bank = bakeAuto(dataset, {.budget = 9});
//   bank->selection;   // JSON: every candidate's validation figures and the choice
//
// Candidates that fit the budget: the paper's one-reference bank; K references blended
// (K + 3 bytes with an albedo); the light models ptm, hsh (order 2 and 3) and rbf and bln
// with as many planes as the budget allows (light_model.h). Some of the dataset's lights are
// left out in turn (every 4th, two folds; each light once for small sets), each candidate is
// baked from the others, and each left-out image is predicted at match strengths 0, 1/4,
// ..., 1 (LutBank::Prediction::match) and compared with the photograph (eval/metrics.h). The
// choice is the highest PSNR among the settings whose histogram L1 stays within 0.002 of
// the one-reference bank's and of the same predictor's matched fully, each by the mean of the
// per-image differences plus its standard error (the histograms are the method's point; the
// predictor only places them). Never a held-out image of an outer evaluation: only `dataset`
// is used.
// A basis that collapses (lights too clustered for it) validates badly and is not chosen.

#include <functional>
#include <optional>

#include "core/bake/bake.h"

namespace btflut {

/// auto's default bound on a candidate's multiply-adds per texel (AutoBakeOptions::decodeBudget).
constexpr std::size_t kDefaultDecodeBudget = 2000;

struct AutoBakeOptions {
    BakeOptions base;  ///< grid, entries, threads, reference, quantiles, regions, ptm, progress
    int budget = 9;    ///< bytes per texel the predictor may store
    /// Multiply-adds per texel its prediction may cost: what a moving light pays per texel on a
    /// GPU. The default keeps a moving light within issue 46's frame targets on llvmpipe
    /// (neural9's 891: 2.9 flat frames moving, 8.7 per fragment, at 1920 x 1080; both grow
    /// about linearly with the multiply-adds, to 5 and 20 near 2,000).
    std::size_t decodeBudget = kDefaultDecodeBudget;
    /// Seconds the learned candidate may train, 0 its default steps: a third for each of its two
    /// folds and the final bake (LearnedOptions::seconds: steps, not the clock, so the bank is
    /// the same).
    double seconds = 3 * kDefaultTrainingSeconds;
    std::optional<float> match;  ///< a fixed match strength instead of the validated one
    /// Banks of views: the fewest samples of each target's quantile function (64 to 512) that
    /// validation finds to cost nothing against base.quantiles; false: base.quantiles as given.
    bool chooseQuantiles = true;
    /// Called with a line per stage (candidates, folds); may be empty.
    std::function<void(const std::string&)> log;
    /// Called with the fraction done (0..1) of the chosen learned model's training in the final
    /// bake; may be empty. (base.progress counts validation's steps, in thousandths: a learned
    /// candidate's folds move within theirs.)
    std::function<void(double)> training;
};

/// The bytes per texel of the smallest candidate for a dataset whose images have
/// `channels` channels (the one-reference bank's: the reference itself).
int smallestBudget(int channels);

/// Bakes the validated choice; refuses a budget below every candidate with a line naming the
/// smallest that works. Rectified sets of several views validate a learned model of the views
/// against the one-reference bank (the only predictor that takes views); other sets of several
/// views, and too few images to leave one out, get the one-reference bank (or, where its
/// reference is constant, the rbf model) and say so in the selection.
Result<LutBank> bakeAuto(const Dataset& dataset, const AutoBakeOptions& options, const ImageProvider& provider = {});

}  // namespace btflut
