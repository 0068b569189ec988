// btflut eval: baking and predicting. Each fold's banks are baked from its training images,
// and every held-out image is predicted through the code users run (the Relighter behind
// `relight`, the PTM, the nearest training image, the 2D texture mapping).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>

#include "cli/eval/eval.h"
#include "cli/eval/neural_rti.h"
#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/inverse/model_fill.h"
#include "core/relight/relighter.h"

namespace btflut::cli::eval {

namespace {

// What bake --predictor auto chose, from the bank's selection: "hsh2 match 0.50".
std::string choiceOf(const LutBank& bank) {
    const nlohmann::json s = nlohmann::json::parse(bank.selection, nullptr, false);
    if (!s.is_object() || !s.contains("chosen")) return "?";
    const nlohmann::json& chosen = s["chosen"];
    char text[96];
    std::snprintf(text, sizeof text, "%s match %.2f", chosen.value("name", std::string("?")).c_str(),
                  chosen.value("match", 1.0));
    return text;
}

// One fold's banks, baked on first use from its training images: one per setting (the base,
// one grey reference, also serves brdf and ptm), each with its relighter. The first fold's
// are saved for the report (bankFiles).
class FoldBanks {
public:
    FoldBanks(std::vector<Variant>& variants, const Dataset& train, bool ptm, bool firstFold,
              const std::filesystem::path& scratch, std::map<std::string, std::string>& bankFiles)
        : m_variants(variants),
          m_train(train),
          m_ptm(ptm),
          m_firstFold(firstFold),
          m_scratch(scratch),
          m_bankFiles(bankFiles) {}

    static Variant::Setting keyOf(const Variant& v) {
        if (v.mode == RenderMode::Lut) return v.setting();
        return {"references", 1, 1, ColourMode::Grey, false, "measured", v.grid, v.domain, std::nullopt, std::nullopt};
    }

    Result<LutBank*> bankFor(Variant& v) {
        const Variant::Setting key = keyOf(v);
        if (!m_banks.count(key))
            if (Status s = bake(v, key); !s) return Error{s.error()};
        LutBank* bank = m_banks[key].get();
        if (m_firstFold && !m_bankFiles.count(v.name)) {
            const std::string path = (m_scratch / (std::to_string(m_bankFiles.size()) + ".btflut")).string();
            if (Status s = saveBank(*bank, path); !s) return Error{s.error()};
            m_bankFiles[v.name] = path;
        }
        return bank;
    }

    const Relighter& relighter(const Variant& v) const { return *m_relighters.at(keyOf(v)); }

private:
    Status bake(const Variant& v, const Variant::Setting& key) {
        Variant setting = v;
        std::tie(setting.predictor, setting.references, setting.regions, setting.colour, setting.filled, setting.target,
                 setting.grid, setting.domain, setting.match, setting.budget) = key;
        const auto start = Clock::now();
        const BakeOptions options = bakeOptionsOf(setting, m_ptm && setting.base());
        // lut auto: bake's validated choice, from the fold's training images alone
        AutoBakeOptions automatic{.base = options, .match = setting.match};
        if (setting.budget) automatic.budget = *setting.budget;
        if (setting.trainingSeconds > 0) automatic.seconds = setting.trainingSeconds;
        Result<LutBank> bank = setting.predictor == "auto" ? bakeAuto(m_train, automatic) : bakeBank(m_train, options);
        if (!bank) return Error{bank.error()};
        if (setting.filled)  // fitted to the training images only
            if (Result<ModelFillReport> fill = fillFromDataset(*bank, m_train, nullptr); !fill)
                return Error{fill.error()};
        const double took = seconds(start);
        m_banks[key] = std::make_unique<LutBank>(std::move(*bank));
        m_relighters[key] = std::make_unique<Relighter>(*m_banks[key]);
        const std::string chosen = setting.predictor == "auto" ? choiceOf(*m_banks[key]) : std::string();
        const LutBank& baked = *m_banks[key];
        for (Variant& other : m_variants)
            if (!other.unmatched() && keyOf(other) == key) {
                // Each fold's bank: lut auto may choose another predictor, and so another size, per fold.
                other.foldBytesPerTexel.push_back(bytesPerTexel(other, baked));
                other.foldMultiplyAdds.push_back(
                    baked.makesLuts() ? static_cast<double>(baked.predictor().multiplyAdds()) : 0.0);
                if (other.mode != RenderMode::Lut) continue;
                other.bakeSeconds.push_back(took);
                if (!chosen.empty()) other.chosen.push_back(chosen);
            }
        return success();
    }

    std::vector<Variant>& m_variants;
    const Dataset& m_train;
    bool m_ptm, m_firstFold;
    const std::filesystem::path& m_scratch;
    std::map<std::string, std::string>& m_bankFiles;
    std::map<Variant::Setting, std::unique_ptr<LutBank>> m_banks;
    std::map<Variant::Setting, std::unique_ptr<Relighter>> m_relighters;
};

Result<Image> loadSameSize(const Dataset& dataset, std::size_t i, const Image& first) {
    Result<Image> image = loadImage(dataset.images[i].path);
    if (!image) return Error{image.error()};
    if (Status s =
            requireSameSize(*image, dataset.images[i].path, first.width, first.height, dataset.images.front().path);
        !s)
        return Error{s.error()};
    return image;
}

// The RTI bases and learned models on their own (unmatched variants), fitted to the fold's
// training images (decoded once): by variant name, what each predicts at a light.
using Rendering = std::function<Image(Direction light, Direction view)>;
namespace {

// "12 epochs, 2088 steps (stopped: early stopping); validation MSE 0.0213 0.0051 ... ; rate 0.01 to 0.001"
std::string trainingSummary(const NeuralRti& n) {
    std::string text = std::to_string(n.epochs.size()) + " epochs, " +
                       std::to_string(n.epochs.empty() ? 0 : n.epochs.back().steps) + " steps (stopped: " + n.stopped +
                       "; kept epoch " + std::to_string(n.bestEpoch) +
                       ", the best validation); validation MSE by epoch";
    char value[64];
    for (const NeuralRtiEpoch& e : n.epochs) {
        std::snprintf(value, sizeof value, " %.3g", e.validationLoss);
        text += value;
    }
    if (!n.epochs.empty()) {
        std::snprintf(value, sizeof value, "; rate %g to %g", static_cast<double>(n.epochs.front().rate),
                      static_cast<double>(n.epochs.back().rate));
        text += value;
    }
    return text;
}

}  // namespace

Result<std::map<std::string, Rendering>> fitBases(std::vector<Variant>& variants, const Dataset& dataset,
                                                  const Fold& fold, const Image& first, const Mask& mask,
                                                  const std::function<void(std::size_t, double)>& progress) {
    std::map<std::string, Rendering> models;
    if (std::none_of(variants.begin(), variants.end(), [](const Variant& v) { return v.unmatched(); })) return models;
    std::vector<Image> decoded;
    std::vector<const Image*> images;
    std::vector<Direction> lights, views;  // views: only a learned model of rectified views reads them
    for (std::size_t i : fold.train) {
        Result<Image> image = loadSameSize(dataset, i, first);
        if (!image) return Error{image.error()};
        decoded.push_back(std::move(*image));
        lights.push_back(dataset.images[i].light);
        if (!dataset.fixedView()) views.push_back(dataset.images[i].view);
    }
    for (const Image& image : decoded) images.push_back(&image);
    std::size_t fitted = 0;  // the fits before this one
    for (Variant& v : variants) {
        if (!v.unmatched()) continue;
        const auto start = Clock::now();
        const std::function<void(double)> within = [&progress, fitted](double f) { progress(fitted, f); };
        ++fitted;
        if (v.neuralRti) {
            Result<NeuralRti> model =
                fitNeuralRti(images, lights, mask, {.seconds = v.trainingSeconds, .progress = within}, dataset.source);
            if (!model) return Error{model.error()};
            v.bakeSeconds.push_back(seconds(start));
            v.training.push_back(trainingSummary(*model));
            v.bytesPerTexel = model->codes;
            const std::vector<int> sizes = model->decoderSizes();  // the light among its inputs, per texel
            v.multiplyAdds = 0;
            for (std::size_t k = 0; k + 1 < sizes.size(); ++k) v.multiplyAdds += sizes[k] * sizes[k + 1];
            models[v.name] = [m = std::make_shared<NeuralRti>(std::move(*model))](Direction l, Direction) {
                return m->render(l);
            };
            continue;
        }
        const FitPointer fit = v.fit->trainedFor(v.trainingSeconds, within);
        Result<UnmatchedModel> model =
            fit->fitUnmatched(FitImages{images, lights, views, mask, false, 0, dataset.source});
        if (!model) return Error{model.error()};
        v.bakeSeconds.push_back(seconds(start));
        v.bytesPerTexel = model->bytesPerTexel;
        v.multiplyAdds = model->multiplyAdds;
        models[v.name] = std::move(model->render);
    }
    return models;
}

// The training image nearest held-out image `info` (its light and view, in the bank's
// domain), decoded once per fold.
Result<Image> nearestTraining(const Dataset& dataset, const Fold& fold, const LutBank& bank, const DatasetImage& info,
                              std::map<std::size_t, Image>& decoded) {
    auto distance = [&](const DatasetImage& m) {
        if (bank.domain == BankDomain::Isotropic) {
            const Point3 a = isotropicPoint(m.light, m.view), b = isotropicPoint(info.light, info.view);
            return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
        }
        return std::hypot(angleBetween(m.light, info.light), angleBetween(m.view, info.view));
    };
    std::size_t nearest = fold.train.front();
    for (std::size_t i : fold.train)
        if (distance(dataset.images[i]) < distance(dataset.images[nearest])) nearest = i;
    if (!decoded.count(nearest)) {
        Result<Image> image = loadImage(dataset.images[nearest].path);
        if (!image) return Error{image.error()};
        decoded.emplace(nearest, std::move(*image));
    }
    return decoded.at(nearest);
}

// The contact sheet's error maps: |prediction - photo| times this, on errorMap's hot scale.
constexpr int kErrorGain = 4;

// errorMap's scale, left to right from 0 to 1/kErrorGain, as a cell of the sheet.
Image errorScale(int width, int height) {
    Image ramp(width, height, 3), flat(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            ramp.at(x, y, 0) = ramp.at(x, y, 1) = ramp.at(x, y, 2) =
                static_cast<float>(x) / static_cast<float>(std::max(1, width - 1)) / kErrorGain;
    Mask all{width, height, std::vector<std::uint8_t>(flat.pixelCount(), 1)};
    return errorMap(ramp, flat, all, kErrorGain);
}

// The L1 of a bank's target at a held-out image's light (`at`: its quantile functions there, a
// region each, weighted by the region's sample texels) against the photograph's histogram:
// banks with a predictor matched on one channel; NaN for others (a bank of LUTs reproduces its
// target: its own L1 is the target's).
double targetL1Of(const LutBank& bank, const BankLookup& at, const Image& photo, const Mask& mask) {
    if (!bank.makesLuts() || bank.channels() != 1) return std::nan("");
    const std::vector<float>& values = at.values;
    const auto samples = static_cast<std::size_t>(bank.prediction.quantiles);
    const auto regions = static_cast<std::size_t>(bank.prediction.regions);
    std::vector<std::vector<float>> quantiles;
    std::vector<double> weights(regions, 0.0);
    for (std::size_t r = 0; r < regions; ++r)
        quantiles.emplace_back(values.begin() + static_cast<std::ptrdiff_t>(r * samples),
                               values.begin() + static_cast<std::ptrdiff_t>((r + 1) * samples));
    const LutBank::Prediction& prediction = bank.prediction;
    for (std::size_t i = 0; i < prediction.mask.inside.size(); ++i)
        if (prediction.mask.inside[i]) weights[prediction.labels.empty() ? 0 : prediction.labels[i]] += 1;
    return targetL1(quantiles, weights, photo, mask);
}

// A variant's bank relit for held-out image `info` through the code users run.
Image relitPrediction(Variant& v, const LutBank& bank, const Relighter& relighter, const DatasetImage& info) {
    const auto start = Clock::now();
    Image predicted;
    if (v.fromGrid && bank.makesLuts())  // the prediction, the LUT from the match grid
        predicted = relighter.apply(relighter.gridFrame(info.light, info.view), true);
    else if (v.fromGrid)  // the classic grid, as an engine reads it
        predicted =
            applyLuts(bank.reference, bank.colour, bank.gridLookup(info.light), bank.entries, bank.targetCode());
    else
        predicted = v.blendedLuts ? relighter.applyBlendingLuts(info.light, info.view, true)
                                  : relighter.apply(relighter.frame(info.light, info.view), true);
    v.relightSeconds.push_back(seconds(start));
    return predicted;
}

}  // namespace

Status predictFolds(std::vector<Variant>& variants, const Dataset& dataset, const std::vector<Fold>& folds,
                    const Image& first, const Mask& mask, bool ptm, const EvalOptions& o,
                    const std::filesystem::path& scratch, std::map<std::string, std::string>& bankFiles,
                    std::vector<std::vector<SheetCell>>& sheet, std::vector<PlotColumn>& sheetHistograms) {
    // Histograms of the contact sheet's bins: the photograph's, then each variant's prediction.
    sheetHistograms.assign(1, {"measured", {}});
    for (const Variant& v : variants) sheetHistograms.push_back({v.name, {}});
    auto histogramOf = [&](const Image& image, const DatasetImage& info) {
        char label[96];
        std::snprintf(label, sizeof label, "%s light %.0f,%.0f view %.0f,%.0f", info.name.c_str(),
                      info.light.thetaDegrees(), info.light.phiDegrees(), info.view.thetaDegrees(),
                      info.view.phiDegrees());
        return imageHistograms(image, mask, label, info.light, info.view, 64, false).front();
    };
    // The contact sheet's --contact lights: spread evenly over every held-out image.
    std::set<std::size_t> heldOut, onSheet;
    for (const Fold& fold : folds) heldOut.insert(fold.test.begin(), fold.test.end());
    const std::vector<std::size_t> tests(heldOut.begin(), heldOut.end());
    const std::size_t sheetLights = std::min<std::size_t>(tests.size(), static_cast<std::size_t>(o.sheetLights));
    for (std::size_t k = 0; k < sheetLights; ++k) onSheet.insert(tests[k * tests.size() / sheetLights]);
    // Progress: a step per bank setting baked, per model fitted alone and per held-out image
    // predicted, in every fold; a fit's training moves within its step (NeuralRTI's takes
    // minutes), so steps count in thousandths.
    constexpr std::size_t kStep = 1000;
    const auto fits = static_cast<std::size_t>(
        std::count_if(variants.begin(), variants.end(), [](const Variant& v) { return v.unmatched(); }));
    std::size_t steps = 0, done = 0;
    for (const Fold& fold : folds) steps += (variants.size() + fits + fold.test.size()) * kStep;
    auto step = [&] {
        done += kStep;
        if (o.progress) o.progress(done, steps);
    };
    auto fitProgress = [&](std::size_t fit, double fraction) {
        if (o.progress)
            o.progress(done + fit * kStep + static_cast<std::size_t>(std::clamp(fraction, 0.0, 1.0) * kStep), steps);
    };
    for (std::size_t f = 0; f < folds.size(); ++f) {
        const Fold& fold = folds[f];
        const Dataset train = subset(dataset, fold.train);
        FoldBanks banks(variants, train, ptm, f == 0, scratch, bankFiles);
        for (Variant& v : variants) {
            if (Result<LutBank*> b = banks.bankFor(v); !b) return Error{b.error()};
            step();
        }
        Result<std::map<std::string, Rendering>> models = fitBases(variants, dataset, fold, first, mask, fitProgress);
        if (!models) return Error{models.error()};
        done += fits * kStep;

        std::map<std::size_t, Image> trainImages;  // nearest: decoded once per fold
        for (std::size_t t : fold.test) {
            const DatasetImage& info = dataset.images[t];
            Result<Image> photo = loadSameSize(dataset, t, first);
            if (!photo) return Error{photo.error()};
            const bool sheetRow = onSheet.count(t) > 0;
            std::vector<SheetCell> errorRow;  // the contact sheet's row under it: where each mode misses
            if (sheetRow) {
                char light[96];  // the view too where the capture has several
                std::snprintf(light, sizeof light,
                              dataset.fixedView() ? "\nlight %.0f, %.0f" : "\nlight %.0f, %.0f view %.0f, %.0f",
                              info.light.thetaDegrees(), info.light.phiDegrees(), info.view.thetaDegrees(),
                              info.view.phiDegrees());
                sheet.push_back({{info.name + " (photo)" + light, *photo}});
                sheetHistograms.front().rows.push_back(histogramOf(*photo, info));
            }
            for (Variant& v : variants) {
                Result<LutBank*> found = banks.bankFor(v);
                if (!found) return Error{found.error()};
                const LutBank& bank = **found;
                v.bankDomain = bank.domain;
                Image predicted;
                if (v.unmatched()) {  // the model decoded at the light: its relight time
                    const auto start = Clock::now();
                    predicted = models->at(v.name)(info.light, info.view);
                    v.relightSeconds.push_back(seconds(start));
                } else if (v.mode == RenderMode::Lut) {
                    predicted = relitPrediction(v, bank, banks.relighter(v), info);
                } else if (v.mode == RenderMode::Ptm) {
                    predicted = bank.ptm.render(info.light);
                } else if (v.mode == RenderMode::Nearest) {  // the nearest measured light-view pair in the domain
                    Result<Image> nearest = nearestTraining(dataset, fold, bank, info, trainImages);
                    if (!nearest) return Error{nearest.error()};
                    predicted = std::move(*nearest);
                } else {
                    predicted = bank.reference;
                    if (v.mode == RenderMode::Brdf) {
                        const float scale =
                            brdfScale(bank, brdfReferenceGrey(bank), bank.lookup(info.light, info.view));
                        for (float& s : predicted.samples) s = std::min(1.f, s * scale);
                    }
                }
                v.errors.push_back(compareImages(predicted, *photo, mask));
                const BankLookup at = bank.lookup(info.light, info.view);
                v.targetL1.push_back(v.mode == RenderMode::Lut && !v.unmatched() ? targetL1Of(bank, at, *photo, mask)
                                                                                 : std::nan(""));
                v.images.push_back(info.name);
                auto beyond = [](Provenance p) { return p == Provenance::Clamped || p == Provenance::Modelled; };
                v.outside.push_back(beyond(at.lightProvenance) || beyond(at.viewProvenance));
                if (sheetRow) {
                    sheetHistograms[static_cast<std::size_t>(&v - variants.data()) + 1].rows.push_back(
                        histogramOf(predicted, info));
                    // Each cell's figures under its name: how close it came to the photograph.
                    const ImageErrors& e = v.errors.back();
                    char figures[64];
                    if (std::isnan(e.psnr)) {  // views not rectified to one frame: no pixels compared
                        std::snprintf(figures, sizeof figures, "\nL1 %.2f", e.l1);
                    } else {
                        std::snprintf(figures, sizeof figures, "\n%.1f dB  L1 %.2f", e.psnr, e.l1);
                        errorRow.push_back({v.name + "\nerror x" + std::to_string(kErrorGain),
                                            errorMap(predicted, *photo, mask, kErrorGain)});
                    }
                    sheet.back().push_back({v.name + figures, std::move(predicted)});
                }
            }
            if (!errorRow.empty()) {  // led by the scale: black no error, white 1/gain and more
                errorRow.insert(errorRow.begin(), {"error scale\n0 to 1/" + std::to_string(kErrorGain) + "+",
                                                   errorScale(photo->width, photo->height)});
                sheet.push_back(std::move(errorRow));
            }
            step();
        }
    }
    return success();
}

}  // namespace btflut::cli::eval
