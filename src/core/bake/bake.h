#pragma once
// Baking a LUT bank from a measured image set (the construction; lut_bank.h is the bank and
// its lookups): every image decoded once, streaming, its histogram counted over the sample
// and matched from the reference's (or kept as a quantile function for banks that make their
// LUTs at run time), then the nodes, triangulations and grids.
//
//   Result<LutBank> bank = bakeBank(dataset, BakeOptions{.references = 4});

#include <functional>
#include <optional>
#include <string>

#include "core/bank/lut_bank.h"
#include "core/data/dataset.h"
#include "core/predict/predictor_fit.h"

namespace btflut {

/// The rule in one place: a bank predicts (makes its LUTs at run time) when it blends
/// several references, has regions (segmented or labelled), takes lrgb's albedo, or relights
/// with a light model; else it is the paper's bank of one reference's LUTs.
inline bool bakePredicts(int references, int regions, bool labels, ColourMode colour, bool model) {
    return references > 1 || regions > 1 || labels || colour == ColourMode::Lrgb || model;
}

struct BakeOptions {
    /// Empty: the image nearest to frontal view, then light, among those whose most common
    /// grey level holds at most a quarter of the sample (else the least tied; bake.cpp).
    std::string referenceName;
    int gridSize = 17;
    int entries = 0;  ///< 0: 256 for an 8-bit reference, 1024 for a 16-bit one
    ColourMode colour = ColourMode::Grey;
    int threads = 0;                   ///< 0: all cores
    bool ptm = false;                  ///< also fit a PTM (ptm.h) to the images of the reference's view
    std::optional<BankDomain> domain;  ///< empty: chosen from the directions (setNodes)
    int references = 1;                ///< K references blended per light (a fixed camera; relighter.h)
    /// Instead of references: a predictor fitted to every image (predictor_fit.h: a light
    /// model, a learned model), relit, then matched. Every image is held in memory while
    /// baking (the fit needs them all).
    FitPointer fit;
    /// The predictor already fitted to these images with these options: used as it is, not
    /// fitted again (auto baking a fold again with fewer quantiles).
    std::shared_ptr<const Predictor> fitted;
    float match = 1;  ///< with a model or references: how far each light's LUT matches (LutBank::Prediction::match)
    LutBank::Prediction::Target target =
        LutBank::Prediction::Target::Measured;  ///< with a model or references (LutBank::Prediction::target)
    bool matchGrid = true;  ///< banks with a predictor: bake the LUTs over the grid (LutBank::matchGridLuts)
    /// Banks with a predictor and measured targets: estimate the target between measured
    /// lights as validation chooses (target_choice.h); false: the blend alone.
    bool fitTargets = true;
    int regions = 1;         ///< regions segmented from the images' responses over the lights
    std::string labelsPath;  ///< instead: a label image (each grey value one region)
    int quantiles = 1024;    ///< samples of the targets' quantile functions (banks that make LUTs)
    /// Called after each image with (done, total); may be empty.
    std::function<void(std::size_t, std::size_t)> progress;

    /// True when these options bake a bank with a predictor (one that makes its LUTs at run
    /// time: LutBank::makesLuts), false for the paper's bank of one reference's LUTs.
    bool predicts() const { return bakePredicts(references, regions, !labelsPath.empty(), colour, fitsModel()); }
    /// True when a predictor is fitted to every image.
    bool fitsModel() const { return fit != nullptr; }
    /// True when the predictor is trained (a learned model): a time bounds it, and it reports
    /// its progress.
    bool trains() const { return fit && fit->trains(); }
    /// A trained predictor's training time (0: its default) and progress (0 to 1; may be empty).
    void setTraining(double seconds, std::function<void(double)> done);
};

/// Sets the options' fit from a `--predictor` name (predictorFitNamed: a light model, a learned
/// one). Nothing when the name names no fit, an error for a number out of range.
std::optional<Status> setModelNamed(BakeOptions& options, const std::string& name);

/// Supplies image `index` of a dataset: decodes it into `storage` and returns &storage, or
/// returns an image it already holds (benchmarks time the baking without the decoding).
using ImageProvider = std::function<Result<const Image*>(std::size_t index, Image& storage)>;

/// Bakes a bank from a dataset: decodes every image once, streaming, so memory holds only
/// the reference and one image per thread. Errors name the file and the problem (corrupt
/// image, sizes differ, mask of another size or empty, constant reference, ...).
/// Without a provider, images are decoded from the dataset's files.
Result<LutBank> bakeBank(const Dataset& dataset, const BakeOptions& options, const ImageProvider& provider = {});

}  // namespace btflut
