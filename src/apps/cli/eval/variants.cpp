// btflut eval: the variants (columns of the report) that the options ask for.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "cli/cli.h"
#include "cli/eval/eval.h"

namespace btflut::cli::eval {

namespace {

Result<std::vector<int>> parseList(const std::string& text, const std::string& flag, int low, int high) {
    std::vector<int> values;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < low || v > high)
            return Error{"--" + flag + " '" + text + "': expected a comma-separated list of integers within " +
                         std::to_string(low) + ".." + std::to_string(high)};
        values.push_back(static_cast<int>(v));
    }
    if (values.empty()) return Error{"--" + flag + " is empty"};
    return values;
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> items;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) items.push_back(item);
    return items;
}

// A comma-separated list of --flag's two choices, at least one.
Result<std::vector<std::string>> parseChoices(const std::string& text, const std::string& flag,
                                              const std::vector<std::string>& allowed) {
    std::vector<std::string> items = split(text);
    if (items.empty()) return Error{"--" + flag + " is empty"};
    std::string words;
    for (std::size_t k = 0; k < allowed.size(); ++k)
        words += (k == 0 ? "" : k + 1 == allowed.size() ? " or " : ", ") + allowed[k];
    for (const std::string& item : items)
        if (std::ranges::find(allowed, item) == allowed.end())
            return Error{"--" + flag + " '" + item + "' is not " + words};
    return items;
}

}  // namespace

// The variants of --modes: each baseline, and each lut one per predictor, colour, K
// references and R regions asked.
Result<std::vector<Variant>> modeVariants(const EvalOptions& o, const std::vector<int>& ks,
                                          const std::vector<int>& rs) {
    std::vector<Variant> variants;
    std::vector<std::string> modes = split(o.modes);
    if (modes.empty()) return Error{"--modes is empty"};
    for (const std::string& name : modes) {
        Result<RenderMode> mode = parseRenderMode(name);
        if (!mode) {
            if (name == "neuralrti") {
                Variant v{name, RenderMode::Flat};
                v.neuralRti = true;
                variants.push_back(v);
                continue;
            } else if (std::optional<Result<FitPointer>> fit = predictorFitNamed(name)) {
                if (!*fit) return Error{"--modes: " + fit->error()};
                Variant v{name, RenderMode::Flat};
                v.fit = **fit;
                variants.push_back(v);
                continue;
            }
        }
        if (!mode)
            return Error{"--modes: '" + name +
                         "' is not a mode eval measures: lut, brdf, nearest, flat, a light model (ptm, hsh, hsh2, "
                         "hsh3, rbf, bln, rbfN, blnN, blnNc), a learned one (neural, neuralN, neuralNwW) or neuralrti "
                         "(the published "
                         "NeuralRTI, unmatched); the default is "
                         "lut,ptm,hsh,rbf,bln,nearest,brdf"};
        if (*mode != RenderMode::Lut) {
            variants.push_back({name, *mode});
            continue;
        }
        for (const std::string& predictor : split(o.predictors)) {
            if (predictor == "references") continue;
            if (predictor == "auto") {
                Variant v{"lut auto", RenderMode::Lut, "auto"};
                variants.push_back(v);
                continue;
            }
            BakeOptions named;
            std::optional<Status> model = setModelNamed(named, predictor);
            if (!model)
                return Error{"--predictor '" + predictor +
                             "' is not auto, references, a basis (ptm, hsh, rbf, bln) or neural"};
            if (!*model) return Error{"--predictor " + model->error()};
            for (const std::string& colourText : split(o.colours)) {
                if (colourText != "grey" && colourText != "rgb")
                    continue;  // a model's colour is its own or matched per channel
                for (int r : rs)
                    variants.push_back({"lut " + predictor + " R" + std::to_string(r) + " " + colourText,
                                        RenderMode::Lut, predictor, 1, r,
                                        colourText == "rgb" ? ColourMode::Rgb : ColourMode::Grey});
            }
        }
        const std::vector<std::string> predictors = split(o.predictors);
        if (std::find(predictors.begin(), predictors.end(), "references") == predictors.end()) continue;
        for (const std::string& colourText : split(o.colours)) {
            if (colourText != "grey" && colourText != "rgb" && colourText != "lrgb")
                return Error{"--colour '" + colourText + "' is not grey, rgb or lrgb"};
            const ColourMode colour = colourText == "rgb"    ? ColourMode::Rgb
                                      : colourText == "lrgb" ? ColourMode::Lrgb
                                                             : ColourMode::Grey;
            for (int k : ks)
                for (int r : rs) {
                    Variant v{"lut K" + std::to_string(k) + " R" + std::to_string(r) + " " + colourText,
                              RenderMode::Lut,
                              "references",
                              k,
                              r,
                              colour};
                    variants.push_back(v);
                    if (o.blendedLuts && k > 1) {
                        v.name += " (LUTs blended)";
                        v.blendedLuts = true;
                        variants.push_back(v);
                    }
                }
        }
    }
    return variants;
}

// The sweeps of --match and --budget over `variants`, and its training time.
Status sweepMatchesAndBudgets(const EvalOptions& o, std::vector<Variant>& variants) {
    // The sweeps: lut variants with a predictor at each match strength, `lut auto` at each budget.
    std::vector<float> strengths;
    for (const std::string& item : split(o.matches)) {
        char* end = nullptr;
        const float s = std::strtof(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !(s >= 0 && s <= 1))
            return Error{"--match '" + o.matches + "': expected a comma-separated list of strengths from 0 to 1"};
        strengths.push_back(s);
    }
    // --budget: bytes per texel (each a lut auto of its own) and at most one training time.
    std::vector<int> budgets;
    double trainingSeconds = 0;
    for (const std::string& item : split(o.budgets)) {
        const bool time = !item.empty() && (item.back() == 's' || item.back() == 'm');
        const std::string number = time ? item.substr(0, item.size() - 1) : item;
        char* end = nullptr;
        const double value = std::strtod(number.c_str(), &end);
        if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value) || value <= 0 ||
            (time && trainingSeconds > 0) || (!time && (value != std::floor(value) || value > 255)))
            return Error{"--budget '" + o.budgets +
                         "': expected bytes per texel from 1 to 255 and at most one training time (90s, 5m), "
                         "a comma-separated list"};
        if (time) {
            trainingSeconds = item.back() == 'm' ? 60 * value : value;
            if (Status s = checkTrainingTime(trainingSeconds, o.budgets); !s) return s;
        } else
            budgets.push_back(static_cast<int>(value));
    }
    for (Variant& v : variants) v.trainingSeconds = trainingSeconds;
    auto sweep = [&](const auto& values, auto applies, auto set) {
        if (values.empty()) return;
        std::vector<Variant> all;
        for (const Variant& v : variants) {
            if (!applies(v)) {
                all.push_back(v);
                continue;
            }
            for (const auto& value : values) {
                Variant r = v;
                set(r, value);
                all.push_back(r);
            }
        }
        variants = std::move(all);
    };
    sweep(
        strengths,
        [](const Variant& v) {
            return v.mode == RenderMode::Lut &&
                   (v.predictor == "auto" ||
                    bakePredicts(v.references, v.regions, false, v.colour, v.predictor != "references"));
        },
        [](Variant& r, float s) {
            char text[32];
            std::snprintf(text, sizeof text, " match %g", static_cast<double>(s));
            r.match = s;
            r.name += text;
        });
    sweep(
        budgets, [](const Variant& v) { return v.mode == RenderMode::Lut && v.predictor == "auto"; },
        [](Variant& r, int b) {
            r.budget = b;
            r.name += " budget " + std::to_string(b);
        });
    return success();
}

Result<std::vector<Variant>> variantsOf(const EvalOptions& o) {
    Result<std::vector<int>> ks = parseList(o.references, "references", 1, 255),
                             rs = parseList(o.regions, "regions", 1, 255), gs = parseList(o.grids, "grid", 2, 257);
    if (!ks) return Error{ks.error()};
    if (!rs) return Error{rs.error()};
    if (!gs) return Error{gs.error()};
    Result<std::vector<Variant>> named = modeVariants(o, *ks, *rs);
    if (!named) return Error{named.error()};
    std::vector<Variant> variants = std::move(*named);
    // Each lut bank clamped, filled from the model, or both.
    Result<std::vector<std::string>> fillChoices = parseChoices(o.fills, "fill", {"clamp", "model"});
    if (!fillChoices) return Error{fillChoices.error()};
    const std::vector<std::string>& fills = *fillChoices;
    std::vector<Variant> all;
    for (const Variant& v : variants)
        for (const std::string& fill : fills) {
            if (v.mode != RenderMode::Lut && fill != fills.front()) continue;
            Variant f = v;
            f.filled = v.mode == RenderMode::Lut && fill == "model";
            if (v.mode == RenderMode::Lut && fills.size() > 1) f.name += fill == "model" ? " fill" : " clamp";
            all.push_back(f);
        }
    variants = std::move(all);
    // Lut variants with a predictor: measured targets (between the lights as validated, or
    // blended alone), the nodes' corrections, or several.
    Result<std::vector<std::string>> targetChoices =
        parseChoices(o.targets, "target", {"measured", "blend", "corrections"});
    if (!targetChoices) return Error{targetChoices.error()};
    const std::vector<std::string>& targets = *targetChoices;
    all.clear();
    for (const Variant& v : variants)
        for (const std::string& t : targets) {
            // Every lut bank estimates its targets between the lights (blend or validated);
            // corrections are for a bank with a predictor (not auto, which chooses its own).
            const bool lut = v.mode == RenderMode::Lut;
            const bool applies =
                lut &&
                (t != "corrections" || (v.predictor != "auto" && bakePredicts(v.references, v.regions, false, v.colour,
                                                                              v.predictor != "references")));
            if (!applies && t != targets.front()) continue;
            Variant r = v;
            r.target = applies ? t : "measured";
            if (applies && targets.size() > 1) r.name += " " + t;
            all.push_back(r);
        }
    variants = std::move(all);
    // Each lut bank at every grid size, its LUTs made at the light, read from the grid, or both.
    Result<std::vector<std::string>> sourceChoices = parseChoices(o.lutSources, "luts", {"exact", "grid"});
    if (!sourceChoices) return Error{sourceChoices.error()};
    const std::vector<std::string>& sources = *sourceChoices;
    all.clear();
    for (const Variant& v : variants)
        for (int g : *gs)
            for (const std::string& s : sources) {
                if (v.mode != RenderMode::Lut && (g != gs->front() || s != sources.front())) continue;
                Variant r = v;
                r.grid = g;
                r.fromGrid = v.mode == RenderMode::Lut && s == "grid";
                if (v.mode == RenderMode::Lut && gs->size() > 1) r.name += " G" + std::to_string(g);
                if (v.mode == RenderMode::Lut && sources.size() > 1) r.name += s == "grid" ? " (grid)" : " (exact)";
                all.push_back(r);
            }
    variants = std::move(all);
    // Each bank in every domain asked (nearest measures its distance there too).
    const std::vector<std::string> domains = split(o.domains);
    if (domains.empty()) return Error{"--domain is empty"};
    for (const std::string& d : domains)
        if (d != "auto" && d != "layers" && d != "isotropic")
            return Error{"--domain '" + d + "' is not auto, layers or isotropic"};
    all.clear();
    for (const Variant& v : variants)
        for (const std::string& d : domains) {
            const bool perDomain = v.mode == RenderMode::Lut || v.mode == RenderMode::Nearest;
            if (!perDomain && d != domains.front()) continue;
            Variant r = v;
            if (d != "auto") r.domain = d == "isotropic" ? BankDomain::Isotropic : BankDomain::Layers;
            if (perDomain && d != "auto") r.name += " " + d;
            all.push_back(r);
        }
    variants = std::move(all);
    if (Status swept = sweepMatchesAndBudgets(o, variants); !swept) return Error{swept.error()};
    // Lut variants first, then the baselines in the order asked.
    std::stable_partition(variants.begin(), variants.end(), [](const Variant& v) { return v.mode == RenderMode::Lut; });
    return variants;
}

Status adaptToViews(EvalOptions& o, const Dataset& dataset) {
    if (dataset.fixedView()) return success();
    std::size_t views = 0;
    for (std::size_t i = 0; i < dataset.images.size(); ++i) {
        bool seen = false;
        for (std::size_t j = 0; j < i && !seen; ++j)
            seen = angleBetween(dataset.images[i].view, dataset.images[j].view) < 1e-9;
        views += !seen;
    }
    const std::string where = dataset.source + " has " + std::to_string(views) + " views";
    const EvalOptions defaults;
    // Rectified views (one frame for every view): a learned model of the view too.
    if (o.modes == defaults.modes) o.modes = dataset.rectified ? "lut,nearest,brdf,neural9" : "lut,nearest,brdf";
    if (o.predictors == defaults.predictors) o.predictors = "references";
    for (const std::string& mode : split(o.modes)) {
        if (predictorTakesViews(mode) && dataset.rectified) continue;
        if (predictorTakesViews(mode))
            return Error{"--modes " + mode +
                         ": a learned model across views needs rectified views (one frame for "
                         "every view: the manifest's \"rectified\": true); " +
                         where};
        if (mode != "lut" && mode != "nearest" && mode != "brdf" && mode != "flat")
            return Error{"--modes " + mode + ": predicts a fixed camera's images only; " + where +
                         " (eval's modes there: lut, nearest, brdf, flat, and neuralN on rectified views)"};
    }
    // lut across views: the paper's bank of one reference, or on rectified views a learned
    // model's bank (a layer per view, matched).
    bool predictorsAcross = true;
    for (const std::string& p : split(o.predictors))
        predictorsAcross =
            predictorsAcross && (p == "references" || ((p == "auto" || predictorTakesViews(p)) && dataset.rectified));
    if (!predictorsAcross || o.references != "1" || o.regions != "1" || o.colours == "lrgb" || o.blendedLuts ||
        o.targets.find("corrections") != std::string::npos)
        return Error{
            "lut across views is the paper's bank of one reference (--references 1, no predictor), or on "
            "rectified views a learned model's (--predictor neuralN, or auto); " +
            where};
    if (o.lutSources != defaults.lutSources) return Error{"--luts grid reads a fixed camera's grid; " + where};
    return success();
}

BakeOptions bakeOptionsOf(const Variant& v, bool ptm) {
    BakeOptions b;
    b.gridSize = v.grid;
    b.domain = v.domain;
    b.references = v.references;
    setModelNamed(b, v.predictor);  // references and auto name no model
    if (v.trainingSeconds > 0) b.setTraining(v.trainingSeconds, {});
    if (v.target == "corrections") b.target = LutBank::Prediction::Target::Corrections;
    b.fitTargets = v.target != "blend";
    if (v.match) b.match = *v.match;
    b.regions = v.regions;
    b.colour = v.colour;
    b.ptm = ptm;
    return b;
}

double bytesPerTexel(const Variant& v, const LutBank& bank) {
    const double reference = bank.reference.channels * (bank.reference.bitDepth / 8.0);
    switch (v.mode) {
        case RenderMode::Lut:
            return bank.predictorBytesPerTexel();
        case RenderMode::Ptm:
            return 9;
        default:
            return reference;
    }
}

}  // namespace btflut::cli::eval
