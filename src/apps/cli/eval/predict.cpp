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
#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/inverse/model_fill.h"
#include "core/relight/relighter.h"

namespace btflut::cli::eval {

Status predictFolds(std::vector<Variant>& variants, const Dataset& dataset, const std::vector<Fold>& folds,
                    const Image& first, const Mask& mask, bool ptm, const EvalOptions& o,
                    const std::filesystem::path& scratch, std::map<std::string, std::string>& bankFiles,
                    std::vector<std::vector<SheetCell>>& sheet, std::vector<PlotColumn>& sheetHistograms) {
    // Histograms of the contact sheet's bins: the photograph's, then each variant's prediction.
    sheetHistograms.assign(1, {"measured", {}});
    for (const Variant& v : variants) sheetHistograms.push_back({v.name, {}});
    auto histogramOf = [&](const Image& image, const DatasetImage& info) {
        char label[96];
        std::snprintf(label, sizeof label, "%s l%.0f,%.0f v%.0f,%.0f", info.name.c_str(), info.light.thetaDegrees(),
                      info.light.phiDegrees(), info.view.thetaDegrees(), info.view.phiDegrees());
        return imageHistograms(image, mask, label, info.light, info.view, 64, false).front();
    };
    // The contact sheet's --contact lights: spread evenly over every held-out image.
    std::set<std::size_t> heldOut, onSheet;
    for (const Fold& fold : folds) heldOut.insert(fold.test.begin(), fold.test.end());
    const std::vector<std::size_t> tests(heldOut.begin(), heldOut.end());
    const std::size_t sheetLights = std::min<std::size_t>(tests.size(), static_cast<std::size_t>(o.sheetLights));
    for (std::size_t k = 0; k < sheetLights; ++k) onSheet.insert(tests[k * tests.size() / sheetLights]);
    for (std::size_t f = 0; f < folds.size(); ++f) {
        const Fold& fold = folds[f];
        const Dataset train = subset(dataset, fold.train);
        // Banks per setting; the base (one grey reference) also serves brdf and ptm.
        std::map<Variant::Setting, std::unique_ptr<LutBank>> banks;
        std::map<Variant::Setting, std::unique_ptr<Relighter>> relighters;
        auto bankFor = [&](Variant& v) -> Result<LutBank*> {
            const auto key = v.mode == RenderMode::Lut ? v.setting()
                                                       : Variant::Setting{"references", 1,     1,      ColourMode::Grey,
                                                                          false,        false, v.grid, v.domain};
            if (!banks.count(key)) {
                Variant setting = v;
                std::tie(setting.predictor, setting.references, setting.regions, setting.colour, setting.filled,
                         setting.corrections, setting.grid, setting.domain) = key;
                const auto start = Clock::now();
                const BakeOptions options = bakeOptionsOf(setting, ptm && setting.base());
                // lut auto: bake's validated choice, from the fold's training images alone
                Result<LutBank> bank =
                    setting.predictor == "auto" ? bakeAuto(train, {.base = options}) : bakeBank(train, options);
                if (!bank) return Error{bank.error()};
                if (setting.filled)  // fitted to the training images only
                    if (Result<ModelFillReport> fill = fillFromDataset(*bank, train, nullptr); !fill)
                        return Error{fill.error()};
                const double took = seconds(start);
                banks[key] = std::make_unique<LutBank>(std::move(*bank));
                relighters[key] = std::make_unique<Relighter>(*banks[key]);
                for (Variant& other : variants)
                    if (other.mode == RenderMode::Lut && other.setting() == key) other.bakeSeconds.push_back(took);
            }
            LutBank* bank = banks[key].get();
            if (f == 0 && !bankFiles.count(v.name)) {
                const std::string path = (scratch / (std::to_string(bankFiles.size()) + ".btflut")).string();
                if (Status s = saveBank(*bank, path); !s) return Error{s.error()};
                bankFiles[v.name] = path;
                v.bytesPerTexel = bytesPerTexel(v, *bank);
            }
            return bank;
        };
        for (Variant& v : variants)
            if (Result<LutBank*> b = bankFor(v); !b) return Error{b.error()};
        // The RTI bases on their own, fitted to the training images (decoded once per fold).
        std::map<std::string, LightModel> models;
        if (std::any_of(variants.begin(), variants.end(), [](const Variant& v) { return v.basis.has_value(); })) {
            std::vector<Image> decoded;
            std::vector<const Image*> images;
            std::vector<Direction> lights;
            for (std::size_t i : fold.train) {
                Result<Image> image = loadImage(dataset.images[i].path);
                if (!image) return Error{image.error()};
                if (Status s = requireSameSize(*image, dataset.images[i].path, first.width, first.height,
                                               dataset.images.front().path);
                    !s)
                    return Error{s.error()};
                decoded.push_back(std::move(*image));
                lights.push_back(dataset.images[i].light);
            }
            for (const Image& image : decoded) images.push_back(&image);
            for (Variant& v : variants) {
                if (!v.basis) continue;
                const auto start = Clock::now();
                Result<LightModel> model = fitLightModel(images, lights, mask, *v.basis, dataset.source);
                if (!model) return Error{model.error()};
                v.bakeSeconds.push_back(seconds(start));
                v.bytesPerTexel = model->bytesPerTexel();
                models[v.name] = std::move(*model);
            }
        }

        std::map<std::size_t, Image> trainImages;  // nearest: decoded once per fold
        for (std::size_t t : fold.test) {
            const DatasetImage& info = dataset.images[t];
            Result<Image> photo = loadImage(info.path);
            if (!photo) return Error{photo.error()};
            if (Status s = requireSameSize(*photo, info.path, first.width, first.height, dataset.images.front().path);
                !s)
                return Error{s.error()};
            const bool sheetRow = onSheet.count(t) > 0;
            if (sheetRow) {
                sheet.push_back({{info.name + " (photo)", *photo}});
                sheetHistograms.front().rows.push_back(histogramOf(*photo, info));
            }
            for (Variant& v : variants) {
                Result<LutBank*> found = bankFor(v);
                if (!found) return Error{found.error()};
                const LutBank& bank = **found;
                v.bankDomain = bank.domain;
                Image predicted;
                if (v.basis) {
                    predicted = models.at(v.name).render(info.light);
                } else if (v.mode == RenderMode::Lut) {
                    const Relighter& relighter = *relighters.at(v.setting());
                    const auto start = Clock::now();
                    if (v.fromGrid && bank.makesLuts())  // the prediction, the LUT from the match grid
                        predicted = relighter.apply(relighter.gridFrame(info.light), true);
                    else if (v.fromGrid)  // the classic grid, as an engine reads it
                        predicted = applyLuts(bank.reference, bank.colour, bank.gridLookup(info.light), bank.entries,
                                              bank.targetCode());
                    else
                        predicted = v.blendedLuts ? relighter.applyBlendingLuts(info.light, info.view, true)
                                                  : relighter.apply(relighter.frame(info.light, info.view), true);
                    v.relightSeconds.push_back(seconds(start));
                } else if (v.mode == RenderMode::Ptm) {
                    predicted = bank.ptm.render(info.light);
                } else if (v.mode == RenderMode::Nearest) {  // the nearest measured light-view pair in the domain
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
                    if (!trainImages.count(nearest)) {
                        Result<Image> image = loadImage(dataset.images[nearest].path);
                        if (!image) return Error{image.error()};
                        trainImages.emplace(nearest, std::move(*image));
                    }
                    predicted = trainImages.at(nearest);
                } else {
                    predicted = bank.reference;
                    if (v.mode == RenderMode::Brdf) {
                        const float scale =
                            brdfScale(bank, brdfReferenceGrey(bank), bank.lookup(info.light, info.view));
                        for (float& s : predicted.samples) s = std::min(1.f, s * scale);
                    }
                }
                v.errors.push_back(compareImages(predicted, *photo, mask));
                v.images.push_back(info.name);
                const BankLookup at = bank.lookup(info.light, info.view);
                auto beyond = [](Provenance p) { return p == Provenance::Clamped || p == Provenance::Modelled; };
                v.outside.push_back(beyond(at.lightProvenance) || beyond(at.viewProvenance));
                if (sheetRow) {
                    sheetHistograms[static_cast<std::size_t>(&v - variants.data()) + 1].rows.push_back(
                        histogramOf(predicted, info));
                    sheet.back().push_back({v.name, std::move(predicted)});
                }
            }
        }
    }
    return success();
}

}  // namespace btflut::cli::eval
