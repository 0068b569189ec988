// Fitting the rough-surface model (core/inverse/fit.h, btflut fit) to noise-free simulated
// histograms (the quadrature at 64 nodes; the fit simulates at 32).
#include <doctest/doctest.h>

#include <cmath>

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/inverse/fit.h"
#include "core/io/file_io.h"
#include "core/physics/geometry.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;
namespace fs = std::filesystem;

namespace {

std::vector<HistogramRow> simulatedRows(const SurfaceModel& model, double smoothing = 0) {
    std::vector<HistogramRow> rows;
    for (const Geometry& g : curetC2())
        rows.push_back({g.name, g.light, g.view,
                        simulateHistogram(
                            model, g.light, g.view,
                            {.method = SimulationMethod::Quadrature, .bins = 64, .nodes = 64, .smooth = smoothing})});
    return rows;
}

}  // namespace

TEST_CASE("fit: Lambertian roughness from noise-free curet-c2 histograms within 1%") {
    for (double r : {0.2, 0.4, 0.6}) {
        const SurfaceModel truth{.roughness = r, .gain = 0.8};
        Result<SurfaceFit> fit = fitSurfaceModel(simulatedRows(truth, 1.0), FitBrdf::Lambert);
        REQUIRE_MESSAGE(fit.ok(), fit.error());
        INFO("r " << r << ": fitted " << fit->model.roughness << " +- " << fit->parameters[0].standardError << ", gain "
                  << fit->model.gain << ", smoothing " << fit->smoothing << ", rms " << fit->rms << ", "
                  << fit->iterations << " iterations, " << fit->seconds << " s");
        MESSAGE("r " << r << ": fitted " << fit->model.roughness << " +- " << fit->parameters[0].standardError
                     << ", gain " << fit->model.gain << ", smoothing " << fit->smoothing << ", rms " << fit->rms << ", "
                     << fit->iterations << " iterations, " << fit->seconds << " s");
        CHECK(std::abs(fit->model.roughness - r) <= 0.01 * r);
        CHECK(std::abs(fit->model.gain - 0.8) <= 0.02);
        REQUIRE(fit->residuals.size() == 11);
    }
}

TEST_CASE("fit: Torrance-Sparrow roughness within 1% and facet width sigma within 5%") {
    for (double r : {0.2, 0.4, 0.6}) {
        const SurfaceModel truth{.roughness = r, .brdf = {.kd = 0, .ks = 1, .sigma = 0.15, .ior = 1.5}, .gain = 0.6};
        Result<SurfaceFit> fit = fitSurfaceModel(simulatedRows(truth, 1.0), FitBrdf::TorranceSparrow);
        REQUIRE_MESSAGE(fit.ok(), fit.error());
        MESSAGE("r " << r << ": fitted " << fit->model.roughness << ", sigma " << fit->model.brdf.sigma << ", ior "
                     << fit->model.brdf.ior << ", gain " << fit->model.gain << ", rms " << fit->rms << ", "
                     << fit->iterations << " iterations, " << fit->seconds << " s");
        CHECK(std::abs(fit->model.roughness - r) <= 0.01 * r);
        CHECK(std::abs(fit->model.brdf.sigma - 0.15) <= 0.05 * 0.15);
    }
}

TEST_CASE("fit: a fit that cannot converge in its iterations says so") {
    const SurfaceModel truth{.roughness = 0.3, .gain = 0.8};
    Result<SurfaceFit> fit = fitSurfaceModel(simulatedRows(truth, 1.0), FitBrdf::Lambert, {.maxIterations = 1});
    REQUIRE_FALSE(fit.ok());
    CHECK(fit.error().find("did not converge") != std::string::npos);
}

TEST_CASE("btflut fit: parameters file that bake --model reads, the plot, and bad input refused") {
    TempDir dir;
    const SurfaceModel truth{.roughness = 0.35, .gain = 0.7};
    std::vector<HistogramRow> rows = simulatedRows(truth, 1.0);
    std::ofstream(dir / "h.csv") << histogramsToCsv(rows);
    CliRun run = runCli({"fit", dir / "h.csv", "-o", dir / "p.json", "--plot", dir / "fit.png"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(run.out.find("roughness") != std::string::npos);
    Result<Bytes> text = readFile(dir / "p.json");
    REQUIRE(text.ok());
    const nlohmann::json params = nlohmann::json::parse(std::string(text->begin(), text->end()));
    CHECK(std::abs(params["roughness"].get<double>() - 0.35) < 0.0035);
    CHECK(params["fit"]["residuals"].size() == 11);
    CHECK(params["fit"]["parameters"][0]["standard_error"].get<double>() > 0);
    CHECK(loadImage(dir / "fit.png").ok());
    // --json prints what the file holds; -q nothing.
    CliRun json = runCli({"fit", dir / "h.csv", "-o", dir / "p2.json", "--json"});
    REQUIRE(json.status == 0);
    CHECK(nlohmann::json::parse(json.out) == nlohmann::json::parse(readText(dir / "p2.json")));
    CliRun quiet = runCli({"fit", dir / "h.csv", "-o", dir / "p3.json", "-q"});
    CHECK(quiet.status == 0);
    CHECK(quiet.out.empty());
    // What bake --model reads.
    Image reference(32, 24, 1);
    for (std::size_t i = 0; i < reference.samples.size(); ++i) reference.samples[i] = static_cast<float>(i % 97) / 96.f;
    REQUIRE(savePng(reference, dir / "ref.png").ok());
    CHECK(runCli({"bake", "--model", dir / "p.json", "--reference", dir / "ref.png", "-o", dir / "m.btflut", "-q"})
              .status == 0);

    // Bad input: one line, non-zero exit, nothing written.
    const std::string out = dir / "x.json";
    rows.resize(2);
    std::ofstream(dir / "two.csv") << histogramsToCsv(rows);
    requireOneLineError(runCli({"fit", dir / "two.csv", "-o", out}),
                        "2 histogram(s) cannot determine the 3 parameters of lambert");
    requireOneLineError(runCli({"fit", dir / "h.csv", "--brdf", "glossy", "-o", out}),
                        "--brdf 'glossy' is not lambert, ts or mix");
    std::ofstream(dir / "mixed.csv")
        << "name,theta_i,phi_i,theta_r,phi_r,b0,b1,b2\na,0,0,0,0,0.5,0.5,0\nb,10,0,0,0,1,0\n";
    CHECK(runCli({"fit", dir / "mixed.csv", "-o", out}).status != 0);
    std::vector<HistogramRow> empty = simulatedRows(truth);
    std::fill(empty[3].bins.begin(), empty[3].bins.end(), 0.0);
    std::ofstream(dir / "empty.csv") << histogramsToCsv(empty);
    requireOneLineError(runCli({"fit", dir / "empty.csv", "-o", out}), "histogram 'c2-4' is empty (no sample pixels)");
    requireOneLineError(runCli({"fit", dir / "h.csv", "-o", dir / "x.txt"}), "x.txt");
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("btflut fit: the roughness of rendered Lambertian height fields within 10%") {
    TempDir dir;
    for (double r : {0.2, 0.4, 0.6}) {
        const std::string folder = dir / ("r" + std::to_string(r));
        REQUIRE(runCli({"synth", "--roughness", std::to_string(r), "--size", "256", "--samples", "1",
                        "--correlation-length", "8", "--geometry", "curet-c2", "-q", "-o", folder})
                    .status == 0);
        CliRun run = runCli({"fit", folder, "-o", folder + ".json"});
        REQUIRE_MESSAGE(run.status == 0, run.err);
        Result<Bytes> text = readFile(folder + ".json");
        REQUIRE(text.ok());
        const double fitted = nlohmann::json::parse(std::string(text->begin(), text->end()))["roughness"].get<double>();
        MESSAGE("rendered r " << r << ": fitted " << fitted);
        CHECK(std::abs(fitted - r) <= 0.1 * r);
    }
}
