// btflut simulate: model histograms of a Gaussian rough surface, in the CSV `hist` writes.
#include <iostream>
#include <memory>

#include "cli/command.h"
#include "cli/model_options.h"
#include "core/histogram/histogram.h"
#include "core/physics/geometry.h"
#include "core/physics/simulate.h"

namespace btflut::cli {

namespace {

struct SimulateOptions {
    bool quiet = false;
    ModelFlags model;
    std::string geometry;
    std::string method = "quadrature";
    std::uint64_t samples = 50000;
    std::uint64_t seed = 1;
    int bins = 64;
    int nodes = 64;
    double smooth = 0;
    int threads = 0;
    std::string output;
};

Status runSimulate(const SimulateOptions& o) {
    if (Status s = requireExtension(o.output, {"csv", "json"}, "output"); !s) return s;
    Result<SurfaceModel> model = modelFromFlags(o.model);
    if (!model) return Error{model.error()};
    Result<SimulationMethod> method = parseSimulationMethod(o.method);
    if (!method) return Error{method.error()};
    Result<std::vector<Geometry>> geometry = parseGeometry(o.geometry);
    if (!geometry) return Error{geometry.error()};
    if (!std::isfinite(o.smooth) || o.smooth < 0) return Error{"--smooth must be a width >= 0 in bins"};
    SimulationOptions options{.method = *method,
                              .bins = o.bins,
                              .samples = o.samples,
                              .seed = o.seed,
                              .nodes = o.nodes,
                              .smooth = o.smooth,
                              .threads = o.threads};
    std::vector<HistogramRow> rows;
    for (const Geometry& g : *geometry)
        rows.push_back({g.name, g.light, g.view, simulateHistogram(*model, g.light, g.view, options)});
    if (Status s = saveHistograms(rows, o.output); !s) return s;
    if (!o.quiet)
        std::cout << "wrote " << o.output << ": " << rows.size() << " histogram(s) of " << o.bins << " bins ("
                  << simulationMethodName(*method) << ")\n";
    return success();
}

}  // namespace

void addSimulateCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<SimulateOptions>();
    CLI::App* app =
        root.add_subcommand("simulate", "Histograms of a Gaussian rough surface (paper section 5) at a geometry");
    addModelOptions(*app, o->model, true);
    app->add_option("--geometry", o->geometry,
                    "curet-c2, curet-specular, THETA_I,PHI_I,THETA_R,PHI_R[;...] or a dataset")
        ->required();
    app->add_option("--method", o->method, "mc-paper, mc (area-weighted), quadrature, quadrature-paper")
        ->capture_default_str();
    app->add_option("--samples", o->samples, "Monte Carlo points")
        ->check(CLI::Range(1ull, 1ull << 40))
        ->capture_default_str();
    app->add_option("--seed", o->seed, "Monte Carlo seed")->capture_default_str();
    app->add_option("--bins", o->bins, "histogram bins")->check(CLI::Range(2, 1 << 16))->capture_default_str();
    app->add_option("--nodes", o->nodes, "quadrature nodes per axis and piece")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    app->add_option("--smooth", o->smooth, "Gaussian smoothing width in bins")->capture_default_str();
    app->add_option("--threads", o->threads, "worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
    app->add_option("-o,--output", o->output, "FILE.csv (as btflut hist writes) or FILE.json")->required();
    addQuietFlag(*app, o->quiet);
    commands.push_back({app, [o] { return runSimulate(*o); }});
}

}  // namespace btflut::cli
