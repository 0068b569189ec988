// Ground truth: synthetic Gaussian height fields, rendered, against the histogram model.
#include <doctest/doctest.h>

#include "core/histogram.h"
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
    auto a = synthesizeHeightField({.size = 512, .roughness = 0.6, .roughnessAcross = 0.15, .angle = angle,
                                    .correlationLength = 10, .seed = 2});
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
            auto area = simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::Quadrature, .nodes = 64});
            auto paper = simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::QuadraturePaper, .nodes = 64});
            const double dArea = earthMoversDistance(truth, area), dPaper = earthMoversDistance(truth, paper);
            INFO("r " << r << " " << g.name << ": area-weighted " << dArea << ", paper " << dPaper);
            CHECK(dArea <= 0.02);
            worstArea = std::max(worstArea, dArea);
            worstPaper = std::max(worstPaper, dPaper);
        }
    }
    MESSAGE("worst EMD to rendered fields, theta <= 60: area-weighted " << worstArea << ", paper's recipe " << worstPaper);
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
