#include "core/inverse/model_fill.h"

#include <cmath>
#include <cstdio>

#include "core/parallel.h"
#include "core/relight/relighter.h"

namespace btflut {

namespace {

constexpr double kRingTheta = 90;  // degrees: the outermost modelled lights (the model holds there)
constexpr int kRingLights = 36;

// The lights of a layer where lookups need the model: the grid nodes inside the disk that its
// measured lights do not enclose, with their neighbours (so the model is resolved around the
// measured hull, where lookups move from the measurements to it), and a ring at the horizon.
std::vector<Direction> unmeasuredLights(const LutBank& bank, const ViewLayer& layer) {
    const int n = bank.gridSize;
    auto inDisk = [&](int i, int j) {
        const DiskPoint p = bank.gridPoint(i, j);
        return p.x * p.x + p.y * p.y < 1 - 1e-12;
    };
    std::vector<char> outside(static_cast<std::size_t>(n) * n, 0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            outside[static_cast<std::size_t>(j) * n + i] =
                inDisk(i, j) && !layer.lights.weightsAt(bank.gridPoint(i, j)).inside;
    std::vector<Direction> lights;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            bool wanted = false;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                    if (i + di >= 0 && i + di < n && j + dj >= 0 && j + dj < n)
                        wanted = wanted || outside[static_cast<std::size_t>(j + dj) * n + i + di];
            if (wanted && inDisk(i, j)) lights.push_back(fromDisk(bank.gridPoint(i, j)));
        }
    for (int k = 0; k < kRingLights; ++k) lights.push_back(Direction::fromDegrees(kRingTheta, 360.0 * k / kRingLights));
    return lights;
}

constexpr int kTransportEntries = 4096;

}  // namespace

Result<ModelFillReport> fillFromModel(LutBank& bank, const ModelBankParams& params, const std::string& description) {
    if (bank.domain != BankDomain::Layers)
        return Error{
            "--fill model fills each view's light disk; this bank interpolates in the isotropic domain "
            "(bake it with --domain layers, or leave it clamped)"};
    if (bank.colour == ColourMode::Rgb)
        return Error{"--fill model: the model gives grey histograms; bake with --colour grey or lrgb"};
    if (bank.makesLuts() && bank.prediction.regions > 1)
        return Error{"--fill model: the model describes the whole sample, not each of --regions"};
    for (const ViewLayer& layer : bank.layers)
        for (const LightNode& node : layer.nodes)
            if (node.modelled) return Error{"the bank already holds modelled nodes"};
    const std::size_t length = bank.nodeLength();

    ModelFillReport report;
    SimulationOptions simulation = params.simulation;
    simulation.threads = 1;  // directions in parallel instead
    for (ViewLayer& layer : bank.layers) {
        std::vector<Direction> lights = unmeasuredLights(bank, layer);
        // A measured light at a modelled direction keeps its measurement.
        std::erase_if(lights, [&](Direction d) {
            return std::ranges::any_of(layer.nodes,
                                       [&](const LightNode& m) { return angleBetween(m.light, d) < 1e-6; });
        });
        std::vector<float> values(lights.size() * length);
        parallelFor(lights.size(), 0, [&](std::size_t i) {
            // The measurements where the light leaves their hull (or at the light, inside
            // it), carried on by the model's change from there: the transport that takes the
            // model's distribution at that point to its distribution at the light.
            const Weights w = layer.lights.weightsAt(toDisk(lights[i]));
            DiskPoint anchor{0, 0};
            std::vector<double> measured(length, 0.0);
            for (int k = 0; k < w.count; ++k) {
                const auto node = static_cast<std::size_t>(w.index[k]);
                const DiskPoint p = layer.lights.points()[node];
                anchor = {anchor.x + w.weight[k] * p.x, anchor.y + w.weight[k] * p.y};
                for (std::size_t e = 0; e < length; ++e) measured[e] += w.weight[k] * layer.nodeLuts[node * length + e];
            }
            const Lut transport =
                matchLut(simulateMass(params.model, fromDisk(anchor), layer.view, simulation),
                         simulateMass(params.model, lights[i], layer.view, simulation), kTransportEntries);
            for (std::size_t e = 0; e < length; ++e)
                values[i * length + e] = transport.apply(static_cast<float>(measured[e]));
        });
        for (const Direction& light : lights) {
            char name[48];
            std::snprintf(name, sizeof name, "model %.1f,%.1f", light.thetaDegrees(), light.phiDegrees());
            layer.nodes.push_back({name, light, true});
        }
        layer.nodeLuts.insert(layer.nodeLuts.end(), values.begin(), values.end());
        report.nodes += lights.size();
    }
    bank.modelFill = report.nodes > 0 ? description : std::string();
    bank.buildTriangulations();
    bank.fillGrids();
    if (bank.makesLuts()) bakeMatchGrid(bank);  // the targets changed: the LUTs over the grid too
    return report;
}

Result<ModelFillReport> fillFromDataset(LutBank& bank, const Dataset& dataset, const ModelBankParams* params,
                                        FitBrdf brdf, const std::vector<HistogramRow>* histograms) {
    std::optional<SurfaceFit> fit;
    ModelBankParams fitted;
    if (!params) {
        constexpr int kBins = kFillHistogramBins;
        Result<std::vector<HistogramRow>> decoded = std::vector<HistogramRow>{};
        if (!histograms) {  // not collected while baking: decoded again
            decoded = histogramsOf(dataset, kBins, false);
            if (!decoded) return Error{decoded.error()};
        }
        Result<SurfaceFit> result = fitSurfaceModel(histograms ? *histograms : *decoded, brdf);
        if (!result) return Error{dataset.source + ": fitting the model to fill from: " + result.error()};
        fit = std::move(*result);
        fitted = fittedModelParams(*fit, kBins);
        params = &fitted;
    }
    Result<ModelFillReport> report = fillFromModel(bank, *params, modelParamsText(*params));
    if (!report) return Error{dataset.source + ": " + report.error()};
    report->fit = std::move(fit);
    return report;
}

}  // namespace btflut
