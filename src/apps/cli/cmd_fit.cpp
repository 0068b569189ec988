// btflut fit: the rough-surface model's parameters from measured histograms (paper 6.1).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/histogram/plot.h"
#include "core/inverse/fit.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"
#include "core/physics/model_bank.h"

namespace btflut::cli {

namespace {

struct FitCommandOptions {
    bool quiet = false;
    bool json = false;
    std::string input;
    std::string brdf = "lambert";
    std::string output;
    std::string plot;
    std::string mask;
    int bins = 64;
};

Result<std::vector<HistogramRow>> readHistograms(const FitCommandOptions& o) {
    if (fileExtension(o.input) != "csv") return datasetHistograms(o.input, o.mask, o.bins, false);
    if (!o.mask.empty()) return Error{"--mask applies to a dataset; " + o.input + " holds histograms already"};
    Result<Bytes> text = readFile(o.input);
    if (!text) return Error{text.error()};
    return parseHistogramCsv(std::string(text->begin(), text->end()), o.input);
}

// The parameters file `bake --model` reads (docs/model-params.md), with the fit's report under
// "fit".
nlohmann::json paramsJson(const SurfaceFit& fit, const std::vector<HistogramRow>& rows, const std::string& input) {
    nlohmann::json out = nlohmann::json::parse(modelParamsText(fittedModelParams(fit, rows.front().bins.size())));
    nlohmann::json report{{"histograms", input},
                          {"bins", rows.front().bins.size()},
                          {"rms", fit.rms},
                          {"iterations", fit.iterations},
                          {"seconds", fit.seconds},
                          {"parameters", nlohmann::json::array()},
                          {"residuals", nlohmann::json::array()}};
    for (const FitParameter& p : fit.parameters)
        report["parameters"].push_back(
            {{"name", p.name},
             {"value", p.value},
             {"standard_error", p.determined() ? nlohmann::json(p.standardError) : nlohmann::json()}});
    for (std::size_t i = 0; i < rows.size(); ++i)
        report["residuals"].push_back({{"name", rows[i].name}, {"rms", fit.residuals[i]}});
    out["fit"] = report;
    return out;
}

Status runFit(const FitCommandOptions& o) {
    if (Status s = requireExtension(o.output, {"json"}, "output"); !s) return s;
    if (!o.plot.empty())
        if (Status s = requireExtension(o.plot, {"png"}, "--plot"); !s) return s;
    Result<FitBrdf> brdf = parseFitBrdf(o.brdf);
    if (!brdf) return Error{"--" + brdf.error()};
    Result<std::vector<HistogramRow>> rows = readHistograms(o);
    if (!rows) return Error{rows.error()};
    for (const HistogramRow& row : *rows) {
        double sum = 0;
        for (double v : row.bins) sum += v;
        if (!(sum > 0)) return Error{o.input + ": histogram '" + row.name + "' is empty (no sample pixels)"};
    }
    Result<SurfaceFit> fit = fitSurfaceModel(*rows, *brdf);
    if (!fit) return Error{o.input + ": " + fit.error()};

    const std::string json = jsonText(paramsJson(*fit, *rows, o.input));
    std::vector<FileContents> files{{o.output, json.data(), json.size()}};
    Bytes plot;
    if (!o.plot.empty()) {
        std::vector<HistogramRow> fitted = *rows;
        for (HistogramRow& row : fitted) row.bins = fittedHistogram(*fit, row);
        plot = encodePng(plotHistograms({{"measured", *rows}, {"fitted", fitted}}), 8);
        files.push_back({o.plot, plot.data(), plot.size()});
    }
    if (Status s = writeFilesAtomically(files); !s) return s;

    if (o.quiet) return success();
    if (o.json) {
        std::cout << json;  // what PARAMS.json holds: the parameters, their errors, the residuals
        return success();
    }
    char line[160];
    std::cout << "fitted " << fitBrdfName(*brdf) << " to " << rows->size() << " histograms of "
              << rows->front().bins.size() << " bins in " << fit->iterations << " iterations (" << fit->seconds
              << " s)\n";
    for (const FitParameter& p : fit->parameters) {
        if (p.determined())
            std::snprintf(line, sizeof line, "  %-10s %10.5f +- %.2g\n", p.name.c_str(), p.value, p.standardError);
        else
            std::snprintf(line, sizeof line, "  %-10s %10.5f   not determined by these histograms\n", p.name.c_str(),
                          p.value);
        std::cout << line;
    }
    std::snprintf(line, sizeof line, "residual (RMS of bin differences): %.3g overall\n", fit->rms);
    std::cout << line;
    for (std::size_t i = 0; i < rows->size(); ++i) {
        std::snprintf(line, sizeof line, "  %-16s %.3g\n", (*rows)[i].name.c_str(), fit->residuals[i]);
        std::cout << line;
    }
    std::cout << "wrote " << o.output << (o.plot.empty() ? "" : " and " + o.plot) << "\n";
    return success();
}

}  // namespace

void addFitCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<FitCommandOptions>();
    CLI::App* app = root.add_subcommand(
        "fit",
        "The rough-surface model's parameters from measured histograms: non-linear least squares over every "
        "direction at once, with standard errors and residuals");
    app->add_option("INPUT", o->input, "HISTS.csv (as btflut hist writes it) or a dataset")->required();
    app->add_option("--brdf", o->brdf,
                    "lambert (r, gain), ts (r, gain, sigma, ior) or mix (r, gain, ks, sigma, ior); "
                    "each with a smoothing width")
        ->capture_default_str();
    app->add_option("-o,--output", o->output, "PARAMS.json (what bake --model reads, with the fit's report)")
        ->required();
    app->add_option("--plot", o->plot, "fit.png: measured and fitted histograms in the paper's layout");
    app->add_option("--bins", o->bins, "bins of a dataset's histograms")
        ->check(CLI::Range(8, 1024))
        ->capture_default_str();
    app->add_option("--mask", o->mask, "a dataset's sample mask instead of its own");
    addQuietFlag(*app, o->quiet);
    app->add_flag("--json", o->json, "print the fit's report as JSON (what PARAMS.json holds)");
    commands.push_back({app, [o] { return runFit(*o); }});
}

}  // namespace btflut::cli
