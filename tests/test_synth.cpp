// Ground truth: synthetic Gaussian height fields, rendered, against the histogram model.
#include <doctest/doctest.h>

#include "core/histogram/histogram.h"
#include "core/physics/geometry.h"
#include "core/physics/simulate.h"
#include "core/synth/render.h"

using namespace btflut;

TEST_CASE("height fields have the requested rms slope, isotropic and anisotropic") {
    for (double r : {0.1, 0.4, 0.8}) {
        auto f = synthesizeHeightField({.size = 256, .roughness = r, .correlationLength = 12, .seed = 5});
        REQUIRE(f.ok());
        CHECK(measuredRmsSlope(*f, 0) == doctest::Approx(r).epsilon(0.02));
        // Isotropic: the same across, and along a diagonal, within sampling scatter.
        CHECK(measuredRmsSlope(*f, std::numbers::pi / 2) == doctest::Approx(r).epsilon(0.1));
        // Independent check of the spectral slopes: finite differences of the heights.
        double sum = 0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const double d = 0.5 * (f->heightAt(x + 1, y) - f->heightAt(x - 1, y));
                sum += d * d;
            }
        CHECK(std::sqrt(sum / (256.0 * 256.0)) == doctest::Approx(r).epsilon(0.02));
    }
    // Corduroy-like: 0.6 along 30 degrees, 0.15 across.
    const double angle = 30 * kDegree;
    auto a = synthesizeHeightField(
        {.size = 512, .roughness = 0.6, .roughnessAcross = 0.15, .angle = angle, .correlationLength = 10, .seed = 2});
    REQUIRE(a.ok());
    CHECK(measuredRmsSlope(*a, angle) == doctest::Approx(0.6).epsilon(0.02));
    CHECK(measuredRmsSlope(*a, angle + std::numbers::pi / 2) == doctest::Approx(0.15).epsilon(0.1));
}

TEST_CASE("height fields are reproducible from their seed; bad specs refused") {
    auto a = synthesizeHeightField({.size = 64, .correlationLength = 8, .seed = 9});
    auto b = synthesizeHeightField({.size = 64, .correlationLength = 8, .seed = 9});
    auto c = synthesizeHeightField({.size = 64, .correlationLength = 8, .seed = 10});
    REQUIRE(a.ok());
    CHECK(a->height == b->height);
    CHECK(a->height != c->height);
    CHECK(synthesizeHeightField({.size = 0}).error().find("size") != std::string::npos);
    CHECK(synthesizeHeightField({.roughness = -1}).error().find("roughness") != std::string::npos);
    CHECK(synthesizeHeightField({.correlationLength = 0}).error().find("correlation length") != std::string::npos);
    CHECK(synthesizeHeightField({.size = 32, .correlationLength = 16}).error().find("size / 4") != std::string::npos);
}

TEST_CASE("rendered height fields: masking, shadowing, and the model's recipes against the truth") {
    // The table (bench/RESULTS.md): Lambertian r 0.2, 0.4, 0.6, fields of 512 x 512,
    // curet-c2 positions where theta_i and theta_r are at most 60 degrees.
    const auto geometry = curetC2();
    double worstArea = 0, worstPaper = 0;
    for (double r : {0.2, 0.4, 0.6}) {
        auto field = synthesizeHeightField({.size = 512, .roughness = r, .correlationLength = 16, .seed = 3});
        REQUIRE(field.ok());
        SurfaceModel model{.roughness = r};
        for (const Geometry& g : geometry) {
            if (g.light.thetaDegrees() > 60 || g.view.thetaDegrees() > 60) continue;
            Image image = renderHeightField(*field, model, g.light, g.view, {.samplesPerAxis = 1});
            auto truth = binHistogram(countGreyLevels(image, fullMask(512, 512)), 64);
            auto area =
                simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::Quadrature, .nodes = 64});
            auto paper =
                simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::QuadraturePaper, .nodes = 64});
            const double dArea = earthMoversDistance(truth, area), dPaper = earthMoversDistance(truth, paper);
            INFO("r " << r << " " << g.name << ": area-weighted " << dArea << ", paper " << dPaper);
            CHECK(dArea <= 0.02);
            worstArea = std::max(worstArea, dArea);
            worstPaper = std::max(worstPaper, dPaper);
        }
    }
    MESSAGE("worst EMD to rendered fields, theta <= 60: area-weighted " << worstArea << ", paper's recipe "
                                                                        << worstPaper);
    CHECK(worstArea < worstPaper);
}

TEST_CASE("a frontal light casts no shadow; a grazing one does, and only where the field rises") {
    auto field = synthesizeHeightField({.size = 128, .roughness = 0.5, .correlationLength = 8, .seed = 4});
    REQUIRE(field.ok());
    SurfaceModel model{.roughness = 0.5, .gain = 0.5};
    Image frontal = renderHeightField(*field, model, {}, {}, {.samplesPerAxis = 1});
    for (float v : frontal.samples) CHECK(v > 0);  // every facet faces a frontal light
    Image grazing = renderHeightField(*field, model, Direction::fromDegrees(80, 0), {}, {.samplesPerAxis = 1});
    std::size_t dark = 0;
    for (float v : grazing.samples) dark += v == 0;
    CHECK(dark > grazing.samples.size() / 10);
    CHECK(dark < grazing.samples.size());
}

#include "core/data/dataset.h"
#include "helpers.h"

using namespace btflut::test;

TEST_CASE("btflut synth writes a dataset every reader takes, reproducibly, atomically") {
    TempDir dir;
    CliRun run = runCli({"synth", "--preset", "corduroy", "--geometry", "rti-6", "--size", "64", "--correlation-length",
                         "6", "--samples", "1", "--albedo-variation", "0.3", "--ambient", "0.05", "--noise", "0.01",
                         "-o", dir / "cord"});
    REQUIRE(run.status == 0);
    auto manifest = openDataset(dir / "cord");
    REQUIRE(manifest.ok());
    CHECK(manifest->format == "manifest");
    CHECK(manifest->images.size() == 6);
    CHECK(fs::exists(dir / "cord/mask.png"));
    auto lp = openDataset(dir / "cord/synth.lp");  // fixed frontal camera: also an RTI capture
    REQUIRE(lp.ok());
    CHECK(angleBetween(lp->images[3].light, manifest->images[3].light) < 1e-6);
    auto image = loadImage(dir / "cord/l2.png");
    REQUIRE(image.ok());
    CHECK(image->width == 64);
    CHECK(image->channels == 1);
    auto synth = nlohmann::json::parse(readText(dir / "cord/btflut-dataset.json"))["synth"];
    CHECK(synth["roughness"] == 0.6);
    CHECK(synth["roughness_across"] == 0.15);
    // It bakes.
    REQUIRE(runCli({"bake", dir / "cord", "-o", dir / "cord.btflut", "-q"}).status == 0);

    // Same flags, same seed: the same bytes (whatever the thread count); --force replaces.
    REQUIRE(runCli({"synth",      "--preset",  "corduroy", "--geometry",
                    "rti-6",      "--size",    "64",       "--correlation-length",
                    "6",          "--samples", "1",        "--albedo-variation",
                    "0.3",        "--ambient", "0.05",     "--noise",
                    "0.01",       "--threads", "1",        "-o",
                    dir / "again"})
                .status == 0);
    CHECK(readText(dir / "again/l4.png") == readText(dir / "cord/l4.png"));
    requireOneLineError(runCli({"synth", "--size", "64", "--correlation-length", "6", "-o", dir / "cord"}),
                        "exists and is not empty (use --force");
    CHECK(readText(dir / "again/l4.png") == readText(dir / "cord/l4.png"));
    REQUIRE(runCli({"synth", "--size", "64", "--correlation-length", "6", "--geometry", "10,0,20,180", "--force",
                    "--depth", "16", "-o", dir / "cord"})
                .status == 0);
    CHECK(fs::exists(dir / "cord/p1.png"));
    CHECK_FALSE(fs::exists(dir / "cord/l4.png"));
    CHECK(loadImage(dir / "cord/p1.png")->bitDepth == 16);
    CHECK_FALSE(fs::exists(dir / "cord/synth.lp"));  // the camera is not frontal
}

TEST_CASE("btflut synth refuses bad input with one line and writes nothing") {
    TempDir dir;
    const std::vector<std::pair<std::vector<std::string>, std::string>> bad{
        {{"--size", "0"}, "size 0 must be positive"},
        {{"--size", "-8"}, "size -8 must be positive"},
        {{"--roughness", "0"}, "roughness 0 must be > 0"},
        {{"--correlation-length", "0"}, "correlation length must be > 0"},
        {{"--size", "64", "--correlation-length", "32"}, "at most size / 4"},
        {{"--preset", "velvet"}, "--preset 'velvet'"},
        {{"--brdf", "ts", "--sigma", "-1"}, "sigma -1 must be > 0"},
        {{"--albedo-variation", "2"}, "--albedo-variation"},
        {{"--noise", "-1"}, "--noise"},
        {{"--geometry", "10,0,90,0"}, "above the horizon"},
        {{"--geometry", "rti-0"}, "rti-N"},
    };
    for (const auto& [flags, needle] : bad) {
        std::vector<std::string> args{"synth", "-o", dir / "out"};
        args.insert(args.end(), flags.begin(), flags.end());
        INFO(needle);
        requireOneLineError(runCli(args), needle);
    }
    CHECK(fs::is_empty(dir.path()));
}
