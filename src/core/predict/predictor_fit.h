#pragma once
// The kinds whose predictor is fitted to every image a bake decodes (a light model, a learned
// model), where the references kind blends images it picks. Each kind defines its fit and its
// entry beside its class (how `--predictor` names it, the candidates auto bake weighs);
// the kinds' registry (kinds.cpp) lists the entries, one line a kind. bake/ asks here and
// names no kind.
//
//   std::optional<Result<FitPointer>> fit = predictorFitNamed("hsh2");  // nothing: not a fit's name
//   Result<PredictorPointer> predictor = (**fit)->fit(FitImages{...});

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/predict/predictor.h"
#include "core/result.h"

namespace btflut {

/// The training time of a trained kind named (bake, eval) or chosen by auto
/// (for each fold and the final bake) when no --budget names one: about 11,700 steps of neural9
/// on RGB. On the concrete (rti-49, 256 x 256, held out every:4, seeds 1-4) it scores 28.9
/// dB mean where the 6,000 steps before scored 26.7, as many as 30 s or 60 s do
/// (bench/RESULTS.md, "How long the learned kind trains").
constexpr double kDefaultTrainingSeconds = 15;
/// The longest training time `--budget` takes (bake, eval): a day. Training stops at kEpochs
/// passes over its samples long before on any capture; a longer time is a typo.
constexpr double kMostTrainingSeconds = 86400;

/// What a fit is given: the images of one view (or rectified views), each one's light.
struct FitImages {
    const std::vector<const Image*>& images;
    const std::vector<Direction>& lights;
    const std::vector<Direction>& views;  ///< rectified views, one per image; empty for one camera
    const Mask& mask;
    bool perChannel;  ///< the predictor's RGB matched per channel (rgb banks)
    int threads;
    const std::string& what;  ///< the dataset, as errors name it
};

/// A kind's model alone, unmatched, as an RTI viewer draws it (eval's modes hsh, rbf, neural):
/// its image at a light (and a view, for a model of rectified views), and its cost a texel.
struct UnmatchedModel {
    std::function<Image(Direction light, Direction view)> render;
    double bytesPerTexel = 0;
    double multiplyAdds = 0;  ///< as drawn
};

class PredictorFit;
struct FitKind;
using FitPointer = std::shared_ptr<const PredictorFit>;
using PredictorPointer = std::shared_ptr<const Predictor>;

/// A kind's options, and how they make its predictor from the images.
class PredictorFit : public std::enable_shared_from_this<PredictorFit> {
public:
    virtual ~PredictorFit() = default;
    /// The kind's family as `--predictor` names it, for messages: "hsh", "rbf", "neural".
    virtual std::string family() const = 0;
    /// The options as text (a cache's key).
    virtual std::string settings() const = 0;
    /// Its kind's entry in the registry (below).
    virtual const FitKind& kind() const = 0;
    /// Trained: a time bounds it, and it reports its progress (its kind's FitKind::trains).
    bool trains() const;
    /// Fits rectified views too (its networks take the view; FitKind::takesViews).
    bool takesViews() const;
    /// The same with a training time (0: its own) and progress (0 to 1; may be empty); itself
    /// when it does not train.
    virtual FitPointer trainedFor(double /*seconds*/, std::function<void(double)> /*progress*/) const {
        return shared_from_this();
    }
    virtual Result<PredictorPointer> fit(const FitImages& in) const = 0;
    /// The model alone (`in.perChannel` unread).
    virtual Result<UnmatchedModel> fitUnmatched(const FitImages& in) const = 0;
};

/// What auto bake weighs a kind's candidates by.
struct CandidateBounds {
    int bytes;       ///< per texel left to the predictor (a region's label taken)
    int channels;    ///< the images' (1 or 3)
    double seconds;  ///< a trained candidate's training time
};

/// A candidate auto bake validates (auto_bake.h).
struct FitCandidate {
    std::string name;
    FitPointer fit;
    int bytes;                 ///< per texel (a colour light model's albedo among them)
    std::size_t multiplyAdds;  ///< a texel's decoding
};

/// A kind in the registry.
struct FitKind {
    /// The fit a `--predictor` name names: nothing when it names another kind, an error for a
    /// number out of range.
    std::optional<Result<FitPointer>> (*named)(const std::string& name);
    bool trains;      ///< its fits train: a time bounds them, and they report their progress
    bool takesViews;  ///< its fits take rectified views
    /// Its candidates for auto bake, cheapest first.
    std::vector<FitCandidate> (*candidates)(const CandidateBounds& bounds);
};

/// A kind's FitKind::named from its options' parser (nothing, an error, or the options) and
/// its fit's maker.
template <auto parse, auto make>
std::optional<Result<FitPointer>> fitNamed(const std::string& name) {
    auto options = parse(name);
    if (!options) return std::nullopt;
    if (!*options) return Result<FitPointer>(Error{options->error()});
    return Result<FitPointer>(make(std::move(**options)));
}

/// The fit a `--predictor` name names, whatever its kind (nothing: no fit's name).
std::optional<Result<FitPointer>> predictorFitNamed(const std::string& name);
/// Whether a `--predictor` name names a trained kind, its numbers in range or not.
bool predictorTrains(const std::string& name);
/// Whether it names a kind that takes rectified views, its numbers in range or not.
bool predictorTakesViews(const std::string& name);
/// Every kind's candidates for auto bake, the kinds in the registry's order.
std::vector<FitCandidate> fitCandidates(const CandidateBounds& bounds);

}  // namespace btflut
