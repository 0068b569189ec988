#include "core/bake/auto_bake.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "core/eval/holdout.h"
#include "core/eval/metrics.h"
#include "core/io/json_text.h"
#include "core/parallel.h"
#include "core/relight/relighter.h"

namespace btflut {

namespace {

// The L1 a choice may give up against the one-reference bank's (the tolerance).
constexpr double kL1Tolerance = 0.002;

struct Candidate {
    std::string name;
    BakeOptions options;
    int bytes = 0;
    bool classic = false;  // the paper's bank: one reference, its LUTs (matched fully by definition)
    std::string skipped;   // why it was not validated (over the budget, its bake failed)
    // Per match strength: sums over the validation images.
    std::map<float, std::pair<double, double>> sums;  // match -> (psnr, l1)
    std::size_t images = 0;
};

std::vector<Candidate> candidatesFor(const BakeOptions& base, int channels, int budget, std::size_t lights) {
    const int region = base.regions > 1 || !base.labelsPath.empty() ? 1 : 0;
    const int albedo = channels == 3 ? 3 : 0;
    std::vector<Candidate> out;
    auto add = [&](std::string name, BakeOptions o, int bytes, bool classic = false) {
        Candidate c{std::move(name), std::move(o), bytes + region, classic};
        if (c.bytes > budget) c.skipped = "needs " + std::to_string(c.bytes) + " bytes per texel";
        out.push_back(std::move(c));
    };
    BakeOptions classic = base;
    classic.references = 1;
    classic.colour = ColourMode::Grey;
    add("K1", classic, channels, true);
    // K references: grey ones with an albedo (colour), or grey ones (grey images).
    const int k = std::min<int>({budget - region - albedo, 16, static_cast<int>(lights) - 1});
    if (k >= 2) {
        BakeOptions refs = classic;
        refs.references = k;
        refs.colour = channels == 3 ? ColourMode::Lrgb : ColourMode::Grey;
        add("K" + std::to_string(k) + (channels == 3 ? " lrgb" : ""), refs, k + albedo);
    }
    auto model = [&](const std::string& name, LightModelOptions m, int bytes) {
        BakeOptions o = classic;
        o.model = m;
        add(name, o, bytes);
    };
    model("ptm", {.basis = LightBasis::Ptm}, 6 + albedo);
    model("hsh2", {.basis = LightBasis::Hsh, .order = 2}, 4 + albedo);
    model("hsh3", {.basis = LightBasis::Hsh, .order = 3}, 9 + albedo);
    const int planes = std::clamp(budget - region, 1, LightModel::kMaxPlanes);
    model("rbf" + std::to_string(planes), {.basis = LightBasis::Rbf, .planes = planes}, planes);
    model("bln" + std::to_string(planes), {.basis = LightBasis::Bilinear, .planes = planes}, planes);
    // Packed: the same bytes holding more components, the trailing ones with 4 bits.
    model("rbf" + std::to_string(planes) + "c", {.basis = LightBasis::Rbf, .planes = planes, .packed = true}, planes);
    model("bln" + std::to_string(planes) + "c", {.basis = LightBasis::Bilinear, .planes = planes, .packed = true},
          planes);
    return out;
}

// The lights left out in turn: every 4th (two folds, a quarter each) for 8 images or more;
// each of up to four spread images alone for fewer; none below 3.
std::vector<Fold> validationFolds(std::size_t n) {
    std::vector<Fold> folds;
    if (n >= 8) {
        for (std::size_t offset : {0, 2}) {
            Fold f;
            for (std::size_t i = 0; i < n; ++i) (i % 4 == offset ? f.test : f.train).push_back(i);
            folds.push_back(std::move(f));
        }
    } else if (n >= 3) {
        for (std::size_t k = 0; k < std::min<std::size_t>(n, 4); ++k) {
            Fold f;
            const std::size_t held = k * n / std::min<std::size_t>(n, 4);
            for (std::size_t i = 0; i < n; ++i) (i == held ? f.test : f.train).push_back(i);
            folds.push_back(std::move(f));
        }
    }
    return folds;
}

}  // namespace

int smallestBudget(int channels) { return channels; }

Result<LutBank> bakeAuto(const Dataset& dataset, const AutoBakeOptions& options, const ImageProvider& provider) {
    auto log = [&](const std::string& line) {
        if (options.log) options.log(line);
    };
    if (dataset.images.empty()) return Error{dataset.source + ": dataset has no images"};
    if (options.match && !(*options.match >= 0 && *options.match <= 1))
        return Error{"--match must be from 0 (not at all) to 1 (fully)"};
    // Every image decoded once; the bakes below read them from memory.
    const std::size_t n = dataset.images.size();
    std::vector<Image> decoded(n);
    std::vector<std::string> errors(n);
    parallelFor(n, options.base.threads, [&](std::size_t i) {
        if (!provider) {
            Result<Image> image = loadImage(dataset.images[i].path);
            if (image)
                decoded[i] = std::move(*image);
            else
                errors[i] = image.error();
            return;
        }
        Image storage;
        Result<const Image*> image = provider(i, storage);
        if (!image)
            errors[i] = image.error();
        else
            decoded[i] = *image == &storage ? std::move(storage) : **image;
    });
    for (const std::string& e : errors)
        if (!e.empty()) return Error{e};
    const Image& first = decoded.front();
    for (std::size_t i = 1; i < n; ++i)
        if (Status s = requireSameSize(decoded[i], dataset.images[i].path, first.width, first.height,
                                       dataset.images.front().path);
            !s)
            return Error{s.error()};
    const ImageProvider cached = [&](std::size_t i, Image&) -> Result<const Image*> { return &decoded[i]; };

    if (options.budget < smallestBudget(first.channels))
        return Error{"--budget " + std::to_string(options.budget) +
                     ": no predictor fits; the smallest budget that works is " +
                     std::to_string(smallestBudget(first.channels)) + " bytes per texel (the one-reference bank)"};
    std::vector<Candidate> candidates = candidatesFor(options.base, first.channels, options.budget, n);
    nlohmann::json selection{
        {"budget", options.budget},
        {"rule", "the highest validation PSNR with histogram L1 within 0.002 of the one-reference bank's"}};
    const std::vector<Fold> folds = dataset.fixedView() ? validationFolds(n) : std::vector<Fold>{};
    Result<Mask> mask = loadDatasetMask(dataset, first.width, first.height);
    if (!mask) return Error{mask.error()};

    const std::vector<float> strengths =
        options.match ? std::vector<float>{*options.match} : std::vector<float>{0.f, 0.25f, 0.5f, 0.75f, 1.f};
    std::size_t steps = 0, done = 0;
    for (const Candidate& c : candidates) steps += c.skipped.empty() ? folds.size() : 0;
    if (!folds.empty())
        log("validating " + std::to_string(steps / folds.size()) + " predictors within " +
            std::to_string(options.budget) + " bytes per texel on " + std::to_string(folds.size()) + " folds of the " +
            std::to_string(n) + " lights");
    for (const Fold& fold : folds) {
        const Dataset train = subset(dataset, fold.train);
        const ImageProvider trainImages = [&](std::size_t i, Image&) -> Result<const Image*> {
            return &decoded[fold.train[i]];
        };
        for (Candidate& c : candidates) {
            if (!c.skipped.empty()) continue;
            BakeOptions o = c.options;
            o.progress = {};
            o.ptm = false;
            o.matchGrid = false;  // validated with exact LUTs; only the chosen bank gets its grid
            auto bank = std::make_unique<LutBank>();
            if (Result<LutBank> baked = bakeBank(train, o, trainImages); baked) {
                *bank = std::move(*baked);
            } else {
                c.skipped = baked.error();
                c.sums.clear();  // a candidate is compared on every fold or on none
                c.images = 0;
                continue;
            }
            const Relighter relighter(*bank);
            for (float strength : c.classic || !bank->makesLuts() ? std::vector<float>{1.f} : strengths) {
                bank->blend.match = strength;  // read by the frames below (one strength at a time)
                std::vector<ImageErrors> figures(fold.test.size());
                parallelFor(fold.test.size(), options.base.threads, [&](std::size_t k) {
                    const DatasetImage& info = dataset.images[fold.test[k]];
                    figures[k] = compareImages(relighter.apply(relighter.frame(info.light, info.view), true),
                                               decoded[fold.test[k]], *mask);
                });
                auto& [psnr, l1] = c.sums[strength];
                for (const ImageErrors& e : figures) psnr += e.psnr, l1 += e.l1;
            }
            c.images += fold.test.size();
            if (options.base.progress) options.base.progress(++done, steps);
        }
    }

    // The choice: the best PSNR among the settings whose L1 the one-reference bank's allows.
    const Candidate& classic = candidates.front();
    double bound = INFINITY;
    if (classic.images > 0) bound = classic.sums.at(1.f).second / static_cast<double>(classic.images) + kL1Tolerance;
    const Candidate* chosen = nullptr;
    float chosenMatch = 1;
    double chosenPsnr = -INFINITY;
    nlohmann::json rows = nlohmann::json::array();
    for (const Candidate& c : candidates) {
        nlohmann::json row{{"name", c.name}, {"bytes", c.bytes}};
        if (!c.skipped.empty() || c.images == 0) {
            row["skipped"] = c.skipped.empty() ? "not validated" : c.skipped;
            rows.push_back(row);
            continue;
        }
        row["validation"] = nlohmann::json::array();
        for (const auto& [strength, sum] : c.sums) {
            const double psnr = sum.first / static_cast<double>(c.images),
                         l1 = sum.second / static_cast<double>(c.images);
            row["validation"].push_back({{"match", strength}, {"psnr", psnr}, {"l1", l1}});
            if (l1 <= bound && psnr > chosenPsnr) chosen = &c, chosenMatch = strength, chosenPsnr = psnr;
        }
        rows.push_back(row);
    }
    selection["candidates"] = rows;
    selection["folds"] = folds.size();
    BakeOptions final = classic.options;
    if (chosen) {
        final = chosen->options;
        final.match = chosenMatch;
        selection["chosen"] = {{"name", chosen->name}, {"match", chosenMatch}, {"bytes", chosen->bytes}};
        log("chose " + chosen->name + (chosen->classic ? "" : ", match " + std::to_string(chosenMatch).substr(0, 4)));
    } else {
        // Nothing validated: several views, or too few images. The one-reference bank, or where
        // its reference is constant over the sample (a grey card, a black set), a model that
        // carries the brightness.
        selection["chosen"] = {{"name", "K1"}, {"match", 1}, {"bytes", classic.bytes}};
        log(!dataset.fixedView() ? "several views: the one-reference bank (the predictors need one view)"
                                 : "too few images to leave one out: the one-reference bank");
    }
    final.progress = options.base.progress;
    Result<LutBank> bank = bakeBank(dataset, final, cached);
    if (!bank && !chosen && dataset.fixedView() && bank.error().find("constant") != std::string::npos) {
        final = candidates.front().options;
        final.model = LightModelOptions{.basis = LightBasis::Rbf,
                                        .planes = std::clamp(options.budget, 1, LightModel::kMaxPlanes)};
        selection["chosen"] = {
            {"name", "rbf" + std::to_string(final.model->planes)}, {"match", 1}, {"bytes", final.model->planes}};
        selection["note"] = "the reference is constant over the sample: a light model carries the brightness";
        log("the reference is constant over the sample: a light model (rbf) carries the brightness");
        bank = bakeBank(dataset, final, cached);
    }
    if (!bank) return Error{bank.error()};
    if (!folds.empty() || selection.contains("note"))  // a bank that was never compared with others stays the paper's
        bank->selection = jsonText(selection, -1);
    return bank;
}

}  // namespace btflut
