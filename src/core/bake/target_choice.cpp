#include "core/bake/target_choice.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/eval/metrics.h"
#include "core/histogram/histogram.h"
#include "core/inverse/model_target.h"
#include "core/io/json_text.h"
#include "core/parallel.h"

namespace btflut {

namespace {

constexpr std::size_t kMaxTargetFolds = 8;
constexpr int kHistogramBins = 64;   // as eval compares histograms (eval/metrics.h)
const std::vector<double> kEqually;  // histogramL1's weights: every entry alike
// A fit is a candidate where its fold's lights number at least two per coefficient (the
// constant included): psm-rock's 11 lights let a degree-2 fit (9 coefficients) look good at
// ten of them in turn and miss the eleventh by 0.08.
constexpr std::size_t kLightsPerTerm = 2;
// And is chosen where it beats the blend by more than two standard errors of the per-light
// differences (about a one-sided 97.5% test).
constexpr double kStandardErrors = 2;

struct Estimator {
    std::string name;
    FitChoice poly;    // the polynomial fitted to the measurements; degree 0: none
    double model = 0;  // the model's share of the correction: 0, kMixed (with the polynomial), 1
};

constexpr double kMixed = 0.5;

// Simplest first: the blend, then by degree, the strongest ridge first (the rule's order);
// with the model, the model alone and mixed half and half with each polynomial.
std::vector<Estimator> estimators(bool withModel) {
    std::vector<Estimator> polys;
    for (int degree = 1; degree <= 5; ++degree)
        for (double ridge : {1e-2, 1e-3, 1e-4, 1e-5}) {
            char name[40];
            std::snprintf(name, sizeof name, "poly%d ridge %g", degree, ridge);
            polys.push_back({name, {degree, ridge}});
        }
    std::vector<Estimator> out{{"blend", {}}};
    out.insert(out.end(), polys.begin(), polys.end());
    if (!withModel) return out;
    out.push_back({"model", {}, 1});
    for (const Estimator& p : polys) out.push_back({"model + " + p.name, p.poly, kMixed});
    return out;
}

// A candidate's correction from the measured lights and their values (regions runs of
// length / regions values each): the polynomial's, the model's, or the two mixed.
TargetFit estimate(const Estimator& e, const std::vector<Direction>& lights, const float* values, std::size_t length,
                   std::size_t regions, const TargetFit& model) {
    TargetFit poly =
        e.poly.degree > 0 ? fitTargets(lights, values, length, std::vector<FitChoice>(regions, e.poly)) : TargetFit{};
    return e.model > 0 ? mixFits(poly, 1 - e.model, model, e.model) : poly;
}

// 64-bin histogram L1 of the distributions of two runs of values (quantile functions, or LUTs
// applied to the reference) whose entries weigh `weights` (empty: equally).
double histogramL1(const float* a, const float* b, std::size_t samples, const std::vector<double>& weights) {
    const std::vector<double> ha = binValues({a, samples}, weights, kHistogramBins),
                              hb = binValues({b, samples}, weights, kHistogramBins);
    double l1 = 0;
    for (std::size_t k = 0; k < ha.size(); ++k) l1 += std::abs(ha[k] - hb[k]);
    return l1;
}

// A bank of one layer: `layer`'s measured nodes that `keep` says, for lookups only.
LutBank trainingBank(const LutBank& bank, const ViewLayer& layer, const std::vector<bool>& keep) {
    LutBank out;
    out.entries = bank.entries;
    out.colour = bank.colour;
    out.gridSize = bank.gridSize;
    out.domain = BankDomain::Layers;
    out.blend.regions = bank.blend.regions;
    out.blend.quantiles = bank.blend.quantiles;
    ViewLayer copy;
    copy.view = layer.view;
    const std::size_t length = bank.nodeLength();
    for (std::size_t n = 0; n < keep.size(); ++n)
        if (keep[n]) {
            copy.nodes.push_back(layer.nodes[n]);
            copy.nodeLuts.insert(copy.nodeLuts.end(), layer.nodeLuts.begin() + static_cast<std::ptrdiff_t>(n * length),
                                 layer.nodeLuts.begin() + static_cast<std::ptrdiff_t>((n + 1) * length));
        }
    out.layers.push_back(std::move(copy));
    out.buildTriangulations();
    return out;
}

// A bank of LUTs is one region.
std::size_t regionsOf(const LutBank& bank) {
    return bank.makesLuts() ? static_cast<std::size_t>(bank.blend.regions) : 1;
}

std::vector<Direction> lightsOf(const ViewLayer& layer) {
    std::vector<Direction> out;
    for (const LightNode& n : layer.nodes) out.push_back(n.light);
    return out;
}

// One layer: every candidate's L1 per region at each measured node, estimated without it.
// errors[candidate][region][node]; NaN where a candidate has more terms than lights to fit.
using Errors = std::vector<std::vector<std::vector<double>>>;

Errors validate(const LutBank& bank, const ViewLayer& layer, std::size_t lights, const std::vector<Estimator>& list,
                const TargetFit& model, const std::vector<std::vector<double>>& weights, int threads) {
    const std::size_t folds = std::min(lights, kMaxTargetFolds);
    const std::size_t regions = regionsOf(bank);
    const std::size_t length = bank.nodeLength(), run = length / regions, samples = bank.segmentLength();
    const std::size_t channels = run / samples;
    Errors errors(list.size(), std::vector<std::vector<double>>(regions, std::vector<double>(lights, NAN)));
    parallelFor(folds, threads, [&](std::size_t fold) {
        std::vector<bool> keep(lights);
        for (std::size_t n = 0; n < lights; ++n) keep[n] = n % folds != fold;
        LutBank training = trainingBank(bank, layer, keep);
        ViewLayer& trained = training.layers.front();
        const std::vector<Direction> trainingLights = lightsOf(trained);
        for (std::size_t c = 0; c < list.size(); ++c) {
            if ((fitTermCount(list[c].poly.degree) + 1) * kLightsPerTerm > trainingLights.size()) continue;
            trained.fit = estimate(list[c], trainingLights, trained.nodeLuts.data(), length, regions, model);
            for (std::size_t n = 0; n < lights; ++n) {
                if (keep[n]) continue;
                const std::vector<float> estimate = training.lookup(layer.nodes[n].light, layer.view).values;
                const float* measured = &layer.nodeLuts[n * length];
                for (std::size_t r = 0; r < regions; ++r) {
                    double sum = 0;
                    for (std::size_t ch = 0; ch < channels; ++ch) {
                        const std::size_t at = r * run + ch * samples;
                        sum += histogramL1(&estimate[at], measured + at, samples,
                                           weights.empty() ? kEqually : weights[ch]);
                    }
                    errors[c][r][n] = sum / static_cast<double>(channels);
                }
            }
        }
    });
    return errors;
}

double mean(const std::vector<double>& v) {
    double sum = 0;
    for (double e : v) sum += e;
    return sum / static_cast<double>(v.size());
}

}  // namespace

void chooseTargetFits(LutBank& bank, int threads, const std::vector<std::vector<double>>& entryWeights) {
    if (bank.domain != BankDomain::Layers ||
        (bank.makesLuts() && bank.blend.target != LutBank::Blend::Target::Measured))
        return;
    const std::size_t regions = regionsOf(bank);
    // The model: where the nodes hold one grey distribution per light and some layer chooses.
    std::optional<ModelTargets> model;
    nlohmann::json modelRow;
    const bool chooses =
        std::ranges::any_of(bank.layers, [](const ViewLayer& l) { return l.measuredNodes >= kMinFitLights; });
    if (chooses && regions == 1 && bank.channels() == 1) {
        const NodeForm form = bank.makesLuts() ? NodeForm{.quantiles = bank.blend.quantiles}
                                               : NodeForm{.entries = bank.entries,
                                                          .reference = entryWeights.empty() ? std::vector<double>{}
                                                                                            : entryWeights.front()};
        Result<ModelTargets> fitted = modelTargetFits(bank, form);
        if (fitted) {
            model = std::move(*fitted);
            modelRow = {{"brdf", "lambert"},
                        {"roughness", model->model.roughness},
                        {"gain", model->model.gain},
                        {"rms", model->rms}};
        } else {
            modelRow = {{"error", fitted.error()}};
        }
    }
    const std::vector<Estimator> list = estimators(model.has_value());
    const TargetFit noModel;
    nlohmann::json layers = nlohmann::json::array();
    for (std::size_t l = 0; l < bank.layers.size(); ++l) {
        ViewLayer& layer = bank.layers[l];
        const TargetFit& modelFit = model ? model->layers[l] : noModel;
        layer.fit = {};
        nlohmann::json row{{"view", {layer.view.thetaDegrees(), layer.view.phiDegrees()}},
                           {"lights", layer.measuredNodes}};
        if (layer.measuredNodes < kMinFitLights) {
            row["skipped"] = "fewer than " + std::to_string(kMinFitLights) + " measured lights: the blend";
            layers.push_back(row);
            continue;
        }
        const Errors errors = validate(bank, layer, layer.measuredNodes, list, modelFit, entryWeights, threads);
        std::vector<FitChoice> chosen(regions);
        std::size_t chosenFirst = 0;  // region 0's (the only one where the model is a candidate)
        nlohmann::json figures = nlohmann::json::array(), names = nlohmann::json::array();
        // Each candidate against the blend, per region, over the measured lights.
        std::vector<std::vector<PairedDifference>> gains(list.size());
        for (std::size_t c = 0; c < list.size(); ++c)
            for (std::size_t r = 0; r < regions; ++r) gains[c].push_back(pairedDifference(errors[c][r], errors[0][r]));
        for (std::size_t r = 0; r < regions; ++r) {
            std::size_t best = 0;  // the blend, unless a fit beats it beyond the nodes' noise
            double bestMean = mean(errors[0][r]);
            for (std::size_t c = 1; c < list.size(); ++c) {
                const PairedDifference& d = gains[c][r];
                if (d.mean + kStandardErrors * d.standardError < 0 && mean(errors[c][r]) < bestMean) {
                    best = c;
                    bestMean = mean(errors[c][r]);
                }
            }
            chosen[r] = list[best].poly;
            if (r == 0) chosenFirst = best;
            names.push_back(list[best].name);
        }
        for (std::size_t c = 0; c < list.size(); ++c) {
            nlohmann::json l1 = nlohmann::json::array(), se = nlohmann::json::array();
            for (std::size_t r = 0; r < regions; ++r) {
                const PairedDifference& d = gains[c][r];
                l1.push_back(std::isnan(d.mean) ? nlohmann::json() : nlohmann::json(mean(errors[c][r])));
                se.push_back(std::isnan(d.mean) ? nlohmann::json() : nlohmann::json(d.standardError));
            }
            figures.push_back({{"name", list[c].name}, {"l1", l1}, {"se_of_difference", se}});
        }
        std::vector<Direction> lights = lightsOf(layer);
        lights.resize(layer.measuredNodes);
        layer.fit = regions == 1
                        ? estimate(list[chosenFirst], lights, layer.nodeLuts.data(), bank.nodeLength(), 1, modelFit)
                        : fitTargets(lights, layer.nodeLuts.data(), bank.nodeLength(), chosen);
        row["folds"] = std::min(layer.measuredNodes, kMaxTargetFolds);
        row["candidates"] = figures;
        row["chosen"] = names;
        layers.push_back(row);
    }
    bank.targetChoice = jsonText(
        {{"rule",
          "per region, the fit of the lowest mean 64-bin L1 at the measured lights (each estimated without it) "
          "among those below the blend's by more than two standard errors of the per-light differences, with two "
          "lights per coefficient; else the blend"},
         {"model", modelRow},
         {"layers", layers}},
        -1);
}

std::string targetChoiceSummary(const LutBank& bank) {
    const nlohmann::json choice = nlohmann::json::parse(bank.targetChoice, nullptr, false);
    std::vector<std::pair<std::string, int>> counts;
    auto count = [&](const std::string& name) {
        auto at = std::ranges::find_if(counts, [&](const auto& c) { return c.first == name; });
        if (at == counts.end())
            counts.emplace_back(name, 1);
        else
            ++at->second;
    };
    if (choice.is_object() && choice.contains("layers") && choice["layers"].is_array())
        for (const nlohmann::json& layer : choice["layers"]) {
            if (!layer.contains("chosen") || !layer["chosen"].is_array()) {
                count("blend");
                continue;
            }
            for (const nlohmann::json& name : layer["chosen"]) count(name.is_string() ? name.get<std::string>() : "?");
        }
    if (counts.empty()) return "blend";
    if (counts.size() == 1) return counts.front().first;
    std::string out;
    if (choice["layers"].size() == 1) {  // one layer: each region's in order
        for (const nlohmann::json& name : choice["layers"][0]["chosen"])
            out += (out.empty() ? "per region: " : ", ") + (name.is_string() ? name.get<std::string>() : "?");
        return out;
    }
    for (const auto& [name, n] : counts) out += (out.empty() ? "" : ", ") + name + " x" + std::to_string(n);
    return out;
}

}  // namespace btflut
