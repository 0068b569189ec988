#pragma once
// `btflut eval` (cmd_eval.cpp) in its parts: the variants the options ask for
// (variants.cpp), baking and predicting the held-out images (predict.cpp), the GL figures
// (measure_gl.cpp) and the report (report.cpp). Internal to the command.

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/bake/bake.h"
#include "core/bank/lut_bank.h"
#include "core/data/dataset.h"
#include "core/data/scene.h"
#include "core/eval/charts.h"
#include "core/eval/holdout.h"
#include "core/eval/metrics.h"
#include "core/histogram/plot.h"
#include "core/predict/light_model.h"

namespace btflut::cli::eval {

using Clock = std::chrono::steady_clock;
inline double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

struct EvalOptions {
    std::string dataset;
    std::string output;
    std::string holdout = "every:4";
    std::string modes = "lut,ptm,hsh,rbf,bln,nearest,brdf";
    std::string references = "1";
    std::string regions = "1";
    std::string colours = "grey";
    std::string predictors = "auto,references";
    std::string fills = "clamp";
    std::string targets = "measured";
    std::string mask;
    std::string backend = "auto";
    bool blendedLuts = false;
    bool json = false;
    bool quiet = false;
    bool noGl = false;
    int frames = 6;
    std::string grids = "17";          ///< banks' grid sizes, a list
    std::string lutSources = "exact";  ///< lut: exact (made at the light), grid (read from the bank's grid), a list
    std::string domains = "auto";      ///< the banks' domains: auto (bake's choice), layers, isotropic, a list
    std::string matches;               ///< lut with a predictor: match strengths, a list; empty: bake's
    /// lut auto: bytes per texel, a list (empty: bake's); and a training time for the learned
    /// kinds (neural, neuralrti, lut auto's candidates): "9,12,300s"
    std::string budgets;
    int sheetLights = 4;
    /// Called with (steps done, steps) as folds' banks are baked and images predicted; may be empty.
    std::function<void(std::size_t, std::size_t)> progress;
};

/// Options a dataset with several views changes: the modes that predict another view (lut,
/// nearest, brdf, flat; one reference per bank). Errors name what cannot be evaluated there.
Status adaptToViews(EvalOptions& o, const Dataset& dataset);

// One column of the report: a mode, and for lut the bank's setting.
struct Variant {
    std::string name;
    RenderMode mode = RenderMode::Lut;
    /// lut: what is matched: references (the --references blended), auto (bake's validated
    /// choice), or a light model's name (ptm, hsh2, rbf9, ...)
    std::string predictor = "references";
    int references = 1, regions = 1;
    ColourMode colour = ColourMode::Grey;
    bool filled = false;    // bake --fill model (fitted to the training images)
    int grid = 17;          // the bank's grid size
    bool fromGrid = false;  // lut: the LUT read from the bank's grid (as an engine does), not made at the light
    /// lut with a predictor: measured (the targets as bake estimates them between the lights),
    /// blend (the measured targets blended alone) or corrections (LutBank::Prediction::Target)
    std::string target = "measured";
    bool blendedLuts = false;                    // the alternative: per-reference LUTs blended
    std::optional<BankDomain> domain;            // the bank's domain (and nearest's distance); empty: bake's choice
    std::optional<float> match;                  // lut with a predictor: the match strength; empty: bake's
    std::optional<int> budget;                   // lut auto: bytes per texel; empty: bake's
    BankDomain bankDomain = BankDomain::Layers;  // what the bank has: `domain`, or bake's choice
    /// An RTI basis or a learned model on its own, unmatched (modes hsh, rbf, bln, neural; a
    /// number after the name is the hsh order, the planes or the codes): fitted to the fold's
    /// training images.
    FitPointer fit;
    bool neuralRti = false;  ///< the published NeuralRTI (neural_rti.h), the learned kind's baseline
    double trainingSeconds =
        0;  ///< the learned kinds' training time (--budget 300s); 0: their own (kDefaultTrainingSeconds)
    bool unmatched() const { return fit || neuralRti; }
    /// The mode as the report names it: the render mode, or the model's kind.
    std::string modeName() const { return fit ? fit->family() : neuralRti ? "neuralrti" : renderModeName(mode); }
    bool base() const {
        return predictor == "references" && references == 1 && regions == 1 && colour == ColourMode::Grey && !filled &&
               target == "measured";
    }
    using Setting = std::tuple<std::string, int, int, ColourMode, bool, std::string, int, std::optional<BankDomain>,
                               std::optional<float>, std::optional<int>>;
    Setting setting() const {
        return {predictor, references, regions, colour, filled, target, grid, domain, match, budget};
    }

    std::vector<ImageErrors> errors;
    std::vector<std::string> images;
    /// Per prediction: the (light, view) bin lies outside the measured hull of the bank's
    /// domain (its lookup extrapolated, or modelled), so the bank clamped (or modelled) it.
    std::vector<bool> outside;
    std::vector<double> bakeSeconds, relightSeconds;
    /// lut with a predictor (grey): per prediction, the L1 of the bank's target at the held-out
    /// light (its estimate of the histogram there) against the photograph's; NaN otherwise.
    std::vector<double> targetL1;
    /// lut auto: what bake chose in each fold ("hsh2 match 0.50"), in fold order.
    std::vector<std::string> chosen;
    std::vector<std::string> training;  ///< neuralrti: each fold's epochs, steps, loss curve and why it stopped
    double bytesPerTexel = 0;           ///< the unmatched models' (the same in every fold)
    /// Banked modes: each fold's bank's bytes per texel and multiply-adds (lut auto may choose
    /// another predictor per fold); the report gives their means.
    std::vector<double> foldBytesPerTexel, foldMultiplyAdds;
    /// Multiply-adds per texel of its prediction (Predictor::multiplyAdds; 0 for the paper's bank).
    double multiplyAdds = 0;
    double gpuBytesPerTexel = std::nan(""), frameMs = std::nan(""), gpuMaxDiff = std::nan("");
};

/// The variants the options ask for, lut settings first.
Result<std::vector<Variant>> variantsOf(const EvalOptions& o);
/// What a lut variant's bank is baked with (`ptm`: also fit the PTM baseline).
BakeOptions bakeOptionsOf(const Variant& v, bool ptm);
/// Data bytes per texel of what a mode draws from (no padding, no mipmaps).
double bytesPerTexel(const Variant& v, const LutBank& bank);

/// Bakes each fold's banks from its training images and predicts its held-out images in
/// every variant (errors, bake and relight times, the contact sheet's cells). Fold 0's banks
/// are saved into `scratch` for the GL figures (bankFiles: variant name to path).
Status predictFolds(std::vector<Variant>& variants, const Dataset& dataset, const std::vector<Fold>& folds,
                    const Image& first, const Mask& mask, bool ptm, const EvalOptions& o,
                    const std::filesystem::path& scratch, std::map<std::string, std::string>& bankFiles,
                    std::vector<std::vector<SheetCell>>& sheet, std::vector<PlotColumn>& sheetHistograms);

/// GL figures per variant: frame times (interleaved rounds, the light moving every frame),
/// texture bytes per texel, and for lut the largest difference of the native renderer from
/// the CPU relighting. `context` gets the GL context's description.
Status measureGl(std::vector<Variant>& variants, const std::map<std::string, std::string>& bankFiles,
                 const Dataset& dataset, const EvalOptions& o, std::string& context);

struct Report {
    std::string text;
    nlohmann::json json;
    std::vector<ChartPanel> tradeoff;  ///< error against bytes per texel, relight and frame time
    std::vector<ChartPanel> byTheta;   ///< error against the held-out light's theta
};

/// The table and its JSON.
Report report(const std::vector<Variant>& variants, const Dataset& dataset, const EvalOptions& o,
              const std::vector<Fold>& folds, std::size_t maskPixels, const std::string& context);
/// eval.txt, eval.json, rows.csv, contact.png, histograms.png, tradeoff.png and
/// error_theta.png into the folder `o.output`, all or none.
Status writeReport(const Report& r, const std::vector<std::vector<SheetCell>>& sheet,
                   const std::vector<PlotColumn>& sheetHistograms, const EvalOptions& o);

}  // namespace btflut::cli::eval
