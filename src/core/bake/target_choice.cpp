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

// The same over the isotropic domain's points.
TargetFit estimatePairs(const Estimator& e, const std::vector<Point3>& points, const float* values, std::size_t length,
                        std::size_t regions, const TargetFit& model) {
    TargetFit poly = e.poly.degree > 0 ? fitPairTargets(points, values, length, std::vector<FitChoice>(regions, e.poly))
                                       : TargetFit{.domain = FitDomain::Pair};
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

// A bank without nodes whose nodes would be of `bank`'s form, in `domain`: for lookups only.
LutBank formOf(const LutBank& bank, BankDomain domain) {
    LutBank out;
    out.entries = bank.entries;
    out.colour = bank.colour;
    out.gridSize = bank.gridSize;
    out.domain = domain;
    out.prediction.regions = bank.prediction.regions;
    out.prediction.quantiles = bank.prediction.quantiles;
    return out;
}

// A bank of one layer: `layer`'s measured nodes that `keep` says, for lookups only.
LutBank trainingBank(const LutBank& bank, const ViewLayer& layer, const std::vector<bool>& keep) {
    LutBank out = formOf(bank, BankDomain::Layers);
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
    return bank.makesLuts() ? static_cast<std::size_t>(bank.prediction.regions) : 1;
}

std::vector<Direction> lightsOf(const ViewLayer& layer) {
    std::vector<Direction> out;
    for (const LightNode& n : layer.nodes) out.push_back(n.light);
    return out;
}

// A node's L1 per region (channels averaged) between its estimate and its measured values,
// into errors[region][node].
void scoreNode(const LutBank& bank, const std::vector<float>& estimate, const float* measured,
               const std::vector<std::vector<double>>& weights, std::vector<std::vector<double>>& errors,
               std::size_t node) {
    const std::size_t regions = regionsOf(bank), run = bank.nodeLength() / regions, samples = bank.segmentLength();
    const std::size_t channels = run / samples;
    for (std::size_t r = 0; r < regions; ++r) {
        double sum = 0;
        for (std::size_t ch = 0; ch < channels; ++ch) {
            const std::size_t at = r * run + ch * samples;
            sum += histogramL1(&estimate[at], measured + at, samples, weights.empty() ? kEqually : weights[ch]);
        }
        errors[r][node] = sum / static_cast<double>(channels);
    }
}

// One layer: every candidate's L1 per region at each measured node, estimated without it.
// errors[candidate][region][node]; NaN where a candidate has more terms than lights to fit.
using Errors = std::vector<std::vector<std::vector<double>>>;

Errors validate(const LutBank& bank, const ViewLayer& layer, std::size_t lights, const std::vector<Estimator>& list,
                const TargetFit& model, const std::vector<std::vector<double>>& weights, int threads) {
    const std::size_t folds = std::min(lights, kMaxTargetFolds);
    const std::size_t regions = regionsOf(bank), length = bank.nodeLength();
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
            for (std::size_t n = 0; n < lights; ++n)
                if (!keep[n])
                    scoreNode(bank, training.lookup(layer.nodes[n].light, layer.view).values,
                              &layer.nodeLuts[n * length], weights, errors[c], n);
        }
    });
    return errors;
}

// Every node's values in the isotropic domain at each point of the bank's pairs: the mean of
// the nodes the symmetry puts there (as lookups average them).
std::vector<float> pointValues(const LutBank& bank) {
    const std::size_t length = bank.nodeLength();
    std::vector<float> out(bank.pairNodes.size() * length, 0.f);
    for (std::size_t p = 0; p < bank.pairNodes.size(); ++p)
        for (const LutBank::NodeRef& n : bank.pairNodes[p])
            for (std::size_t k = 0; k < length; ++k)
                out[p * length + k] +=
                    bank.layers[n.layer].nodeLuts[n.node * length + k] / static_cast<float>(bank.pairNodes[p].size());
    return out;
}

// The isotropic domain: every candidate's L1 per region at each measured pair's point,
// estimated without it (folds of every eighth point), through a bank of the other points.
// `values`: pointValues(bank).
Errors validatePairs(const LutBank& bank, const std::vector<float>& values, const std::vector<Estimator>& list,
                     const TargetFit& model, const std::vector<std::vector<double>>& weights, int threads) {
    const std::size_t points = bank.pairNodes.size(), folds = std::min(points, kMaxTargetFolds);
    const std::size_t regions = regionsOf(bank), length = bank.nodeLength();
    Errors errors(list.size(), std::vector<std::vector<double>>(regions, std::vector<double>(points, NAN)));
    parallelFor(folds, threads, [&](std::size_t fold) {
        LutBank training = formOf(bank, BankDomain::Isotropic);  // the nodes at the kept points
        std::vector<std::vector<bool>> kept(bank.layers.size());
        for (std::size_t l = 0; l < bank.layers.size(); ++l) kept[l].assign(bank.layers[l].nodes.size(), false);
        for (std::size_t p = 0; p < points; ++p)
            for (const LutBank::NodeRef& n : bank.pairNodes[p]) kept[n.layer][n.node] = p % folds != fold;
        for (std::size_t l = 0; l < bank.layers.size(); ++l) {
            const ViewLayer& from = bank.layers[l];
            ViewLayer layer;
            layer.view = from.view;
            for (std::size_t n = 0; n < from.nodes.size(); ++n)
                if (kept[l][n]) {
                    layer.nodes.push_back(from.nodes[n]);
                    layer.nodeLuts.insert(layer.nodeLuts.end(),
                                          from.nodeLuts.begin() + static_cast<std::ptrdiff_t>(n * length),
                                          from.nodeLuts.begin() + static_cast<std::ptrdiff_t>((n + 1) * length));
                }
            if (!layer.nodes.empty()) training.layers.push_back(std::move(layer));
        }
        training.buildTriangulations();
        const std::vector<Point3>& trainingPoints = training.pairs.points();
        const std::vector<float> trainingValues = pointValues(training);
        for (std::size_t c = 0; c < list.size(); ++c) {
            if ((pairTermCount(list[c].poly.degree) + 1) * kLightsPerTerm > trainingPoints.size()) continue;
            training.pairFit = estimatePairs(list[c], trainingPoints, trainingValues.data(), length, regions, model);
            for (std::size_t p = fold; p < points; p += folds) {
                const LutBank::NodeRef n = bank.pairNodes[p].front();
                scoreNode(bank,
                          training.lookup(bank.layers[n.layer].nodes[n.node].light, bank.layers[n.layer].view).values,
                          &values[p * length], weights, errors[c], p);
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

// What the rule chose from one set of validation figures: per region the candidate, its name,
// and every candidate's figures for the record.
struct EstimatorPick {
    std::vector<std::size_t> chosen;  // per region, an index of the list
    nlohmann::json names = nlohmann::json::array(), figures = nlohmann::json::array();
};

EstimatorPick choose(const Errors& errors, const std::vector<Estimator>& list, std::size_t regions) {
    EstimatorPick out;
    // Each candidate against the blend, per region, over the measured nodes.
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
        out.chosen.push_back(best);
        out.names.push_back(list[best].name);
    }
    for (std::size_t c = 0; c < list.size(); ++c) {
        nlohmann::json l1 = nlohmann::json::array(), se = nlohmann::json::array();
        for (std::size_t r = 0; r < regions; ++r) {
            const PairedDifference& d = gains[c][r];
            l1.push_back(std::isnan(d.mean) ? nlohmann::json() : nlohmann::json(mean(errors[c][r])));
            se.push_back(std::isnan(d.mean) ? nlohmann::json() : nlohmann::json(d.standardError));
        }
        out.figures.push_back({{"name", list[c].name}, {"l1", l1}, {"se_of_difference", se}});
    }
    return out;
}

std::vector<FitChoice> polysOf(const EstimatorPick& choice, const std::vector<Estimator>& list) {
    std::vector<FitChoice> out;
    for (std::size_t c : choice.chosen) out.push_back(list[c].poly);
    return out;
}

// The isotropic domain: one estimate over every measured pair, chosen as a layer's is.
nlohmann::json choosePairFit(LutBank& bank, const std::vector<Estimator>& list, const TargetFit& model,
                             const std::vector<std::vector<double>>& weights, int threads) {
    const std::size_t regions = regionsOf(bank), points = bank.pairNodes.size();
    bank.pairFit = {};
    nlohmann::json row{{"domain", "pairs"}, {"lights", points}};
    if (points < kMinFitLights) {
        row["skipped"] = "fewer than " + std::to_string(kMinFitLights) + " measured light and view pairs: the blend";
        return row;
    }
    const std::vector<float> values = pointValues(bank);
    const EstimatorPick choice = choose(validatePairs(bank, values, list, model, weights, threads), list, regions);
    bank.pairFit =
        regions == 1
            ? estimatePairs(list[choice.chosen[0]], bank.pairs.points(), values.data(), bank.nodeLength(), 1, model)
            : fitPairTargets(bank.pairs.points(), values.data(), bank.nodeLength(), polysOf(choice, list));
    row["folds"] = std::min(points, kMaxTargetFolds);
    row["candidates"] = choice.figures;
    row["chosen"] = choice.names;
    return row;
}

}  // namespace

void chooseTargetFits(LutBank& bank, int threads, const std::vector<std::vector<double>>& entryWeights) {
    if (bank.makesLuts() && bank.prediction.target != LutBank::Prediction::Target::Measured) return;
    const bool pairs = bank.domain == BankDomain::Isotropic;
    // Model-filled nodes stand where nothing was measured: the isotropic choice has none.
    if (pairs && std::ranges::any_of(bank.layers, [](const ViewLayer& l) { return l.measuredNodes < l.nodes.size(); }))
        return;
    const std::size_t regions = regionsOf(bank);
    // The model: where the nodes hold one grey distribution per light and some layer chooses.
    std::optional<ModelTargets> model;
    nlohmann::json modelRow;
    const bool chooses =
        pairs ? bank.pairNodes.size() >= kMinFitLights
              : std::ranges::any_of(bank.layers, [](const ViewLayer& l) { return l.measuredNodes >= kMinFitLights; });
    if (chooses && regions == 1 && bank.channels() == 1) {
        const NodeForm form = bank.makesLuts() ? NodeForm{.quantiles = bank.prediction.quantiles}
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
    nlohmann::json layers = nlohmann::json::array();
    if (pairs) {
        layers.push_back(choosePairFit(bank, list, model ? model->pairs : TargetFit{.domain = FitDomain::Pair},
                                       entryWeights, threads));
    } else {
        const TargetFit noModel;
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
            const EstimatorPick choice = choose(
                validate(bank, layer, layer.measuredNodes, list, modelFit, entryWeights, threads), list, regions);
            std::vector<Direction> lights = lightsOf(layer);
            lights.resize(layer.measuredNodes);
            layer.fit =
                regions == 1
                    ? estimate(list[choice.chosen[0]], lights, layer.nodeLuts.data(), bank.nodeLength(), 1, modelFit)
                    : fitTargets(lights, layer.nodeLuts.data(), bank.nodeLength(), polysOf(choice, list));
            row["folds"] = std::min(layer.measuredNodes, kMaxTargetFolds);
            row["candidates"] = choice.figures;
            row["chosen"] = choice.names;
            layers.push_back(row);
        }
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
