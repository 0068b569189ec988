#include "core/inverse/material_histograms.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/bank/bank_file.h"
#include "core/io/file_io.h"

namespace btflut {

namespace {

void deposit(std::vector<double>& histogram, double value, double mass) {
    const auto bins = static_cast<int>(histogram.size());
    histogram[static_cast<std::size_t>(std::clamp(static_cast<int>(value * bins), 0, bins - 1))] += mass;
}

}  // namespace

std::vector<double> MaterialHistograms::at(Direction light, Direction view, int bins, int nodes) const {
    if (model) {
        SimulationOptions options = model->simulation;
        options.method = SimulationMethod::Quadrature;
        options.smooth = model->simulation.smooth * bins / model->simulation.bins;  // given in the file's bins
        options.bins = bins;
        options.nodes = nodes;
        options.threads = 1;
        return simulateHistogram(model->model, light, view, options);
    }
    std::vector<double> histogram(static_cast<std::size_t>(bins), 0.0);
    const BankLookup lookup = bank->lookup(light, view);
    if (bank->makesLuts()) {  // regions x quantiles: each quantile sample an equal share of its region
        const auto q = static_cast<std::size_t>(bank->prediction.quantiles);
        for (std::size_t r = 0; r < regionShares.size(); ++r)
            for (std::size_t m = 0; m < q; ++m)
                deposit(histogram, lookup.values[r * q + m], regionShares[r] / static_cast<double>(q));
        return histogram;
    }
    const double total = static_cast<double>(referenceGrey.total());
    for (std::size_t k = 0; k < referenceGrey.counts.size(); ++k)
        if (referenceGrey.counts[k])
            deposit(histogram,
                    Lut::applyLut(lookup.values.data(), bank->entries, static_cast<float>(referenceGrey.valueOf(k))),
                    static_cast<double>(referenceGrey.counts[k]) / total);
    return histogram;
}

Result<MaterialHistograms> loadMaterial(const std::string& path) {
    MaterialHistograms material;
    material.path = path;
    material.name = std::filesystem::path(path).stem().string();
    const std::string extension = fileExtension(path);
    if (extension == "json") {
        Result<ModelBankParams> params = loadModelParams(path);
        if (!params) return Error{params.error()};
        material.model = std::move(*params);
        return material;
    }
    if (extension != "btflut") return Error{path + ": a material is a model's PARAMS.json or a bank's .btflut"};
    Result<LutBank> bank = loadBank(path, {.ptm = false, .grids = false});
    if (!bank) return Error{bank.error()};
    if (bank->colour == ColourMode::Rgb)
        return Error{path +
                     ": an rgb bank has no grey LUTs to compare histograms with (bake with --colour grey or lrgb)"};
    if (bank->reference.samples.empty())
        return Error{path + ": the bank holds no reference image (baked with --no-reference)"};
    if (bank->makesLuts()) {
        const LutBank::Prediction& prediction = bank->prediction;
        material.regionShares.assign(static_cast<std::size_t>(prediction.regions), 0.0);
        for (std::size_t i = 0; i < prediction.mask.inside.size(); ++i)
            if (prediction.mask.inside[i])
                material.regionShares[prediction.labels.empty() ? 0 : prediction.labels[i]] += 1;
        const double total = static_cast<double>(prediction.mask.count());
        for (double& share : material.regionShares) share /= total;
    } else {
        material.referenceGrey =
            countGreyLevels(bank->reference, fullMask(bank->reference.width, bank->reference.height));
    }
    material.bank = std::make_shared<const LutBank>(std::move(*bank));
    return material;
}

}  // namespace btflut
