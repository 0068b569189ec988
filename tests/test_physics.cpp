#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/histogram/histogram.h"
#include "core/physics/geometry.h"
#include "core/physics/simulate.h"

using namespace btflut;

namespace {

// Lambda from its definition, Lambda(mu) = (1/mu) int_mu^inf (q - mu) p(q) dq with p the
// normal slope density of standard deviation r and mu = cot(theta), by composite Simpson
// after factoring out exp(-b^2 / 2), b = mu / r.
double lambdaByIntegration(double r, double theta) {
    const double mu = 1 / std::tan(theta), b = mu / r;
    const double end = std::min(40.0, 80.0 / b);
    const int n = 20000;
    const double h = end / n;
    auto f = [b](double s) { return s * std::exp(-0.5 * s * s - b * s); };
    double sum = f(0) + f(end);
    for (int i = 1; i < n; ++i) sum += f(i * h) * (i % 2 ? 4 : 2);
    const double integral = sum * h / 3;
    return r / mu * std::exp(-0.5 * b * b) / std::sqrt(2 * std::numbers::pi) * integral;
}

double meanOf(const std::vector<double>& h) {
    double m = 0;
    for (std::size_t i = 0; i < h.size(); ++i) m += h[i] * (i + 0.5) / static_cast<double>(h.size());
    return m;
}

double stdOf(const std::vector<double>& h) {
    const double m = meanOf(h);
    double v = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const double x = (i + 0.5) / static_cast<double>(h.size()) - m;
        v += h[i] * x * x;
    }
    return std::sqrt(v);
}

const SimulationMethod kMethods[] = {SimulationMethod::McPaper, SimulationMethod::Mc, SimulationMethod::Quadrature};

}  // namespace

TEST_CASE("Smith's Lambda matches its definition to 1e-9 and stays finite") {
    CHECK(smithLambda(0.4, 0) == 0.0);
    for (double r : {1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 0.5, 1.0, 2.0, 5.0, 10.0})
        for (double deg : {1e-6, 1e-3, 0.1, 1.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0, 89.9, 89.999, 90 - 1e-6}) {
            const double theta = deg * kDegree;
            const double lambda = smithLambda(r, theta), reference = lambdaByIntegration(r, theta);
            INFO("r " << r << " theta " << deg << ": " << lambda << " vs " << reference);
            REQUIRE(std::isfinite(lambda));
            if (reference < 1e-290)
                CHECK(lambda < 1e-290);
            else
                CHECK(std::abs(lambda - reference) <= 1e-9 * reference);
            const double p = smithUnoccluded(r, theta);
            CHECK((p >= 0 && p <= 1));
        }
    for (double r : {1e-3, 1.0, 10.0}) {
        CHECK(std::isfinite(smithLambda(r, std::numbers::pi / 2)));
        CHECK(smithUnoccluded(r, std::numbers::pi / 2) == 0.0);
        CHECK(smithUnoccluded(r, 0) == 1.0);
    }
}

TEST_CASE("white furnace: the visible facets' projected area is the macro area's") {
    for (double r : {0.01, 0.05, 0.2, 0.4, 1.0, 3.0})
        for (double deg : {0.0, 10.0, 30.0, 60.0, 80.0, 89.0, 89.5}) {
            const double theta = deg * kDegree;
            const double expected = std::cos(theta) * (1 + smithLambda(r, theta));
            INFO("r " << r << " theta_v " << deg);
            CHECK(std::abs(projectedVisibleArea(r, theta) - expected) <= 1e-6 * expected);
        }
    for (double r : {0.1, 0.5, 2.0})
        for (double deg : {0.0, 45.0, 85.0}) {
            const double theta = deg * kDegree;
            const double expected = std::cos(theta) * (1 + smithLambda(r, theta));
            Estimate mc = projectedVisibleAreaMc(r, Direction::fromDegrees(deg, 37), 200000, 11);
            INFO("r " << r << " theta_v " << deg << ": " << mc.mean << " +- " << mc.standardError);
            CHECK(std::abs(mc.mean - expected) <= 4 * mc.standardError + 1e-15);
        }
}

TEST_CASE("Fresnel: 0.04 at normal incidence for n = 1.5, 1 at grazing, Brewster at atan(n)") {
    CHECK(fresnel(1.5, 0).unpolarised() == doctest::Approx(0.04).epsilon(1e-12));
    CHECK(fresnel(1.5, std::numbers::pi / 2).unpolarised() == doctest::Approx(1.0));
    for (double n : {1.2, 1.5, 2.4}) {
        CHECK(fresnel(n, std::atan(n)).p < 1e-28);
        CHECK(fresnel(n, std::atan(n) + 0.05).p > 1e-5);
    }
    CHECK(fresnel(1.0, 0.7).unpolarised() == 0.0);
}

TEST_CASE("curet-c2 and curet-specular geometries") {
    auto c2 = curetC2();
    REQUIRE(c2.size() == 11);
    CHECK(c2[3].light.thetaDegrees() == doctest::Approx(0));  // L: frontal to the lamp
    CHECK(c2[3].view.thetaDegrees() == doctest::Approx(45));
    CHECK(c2[5].light.thetaDegrees() == doctest::Approx(22.5));  // S: specular
    CHECK(c2[5].view.thetaDegrees() == doctest::Approx(22.5));
    CHECK(std::abs(c2[5].light.phiDegrees() - c2[5].view.phiDegrees()) == doctest::Approx(180));
    CHECK(c2[7].view.thetaDegrees() == doctest::Approx(0));  // C: frontal to the camera
    CHECK(c2[10].light.thetaDegrees() == doctest::Approx(78.75));
    CHECK(c2[10].view.thetaDegrees() == doctest::Approx(33.75));
    CHECK(c2[10].light.phiDegrees() == doctest::Approx(c2[10].view.phiDegrees()));  // same side
    auto sp = curetSpecular();
    REQUIRE(sp.size() == 7);
    CHECK(sp[6].light.thetaDegrees() == doctest::Approx(78.75));
    auto list = parseGeometry("10,0,20,180;0,0,0,0");
    REQUIRE(list.ok());
    CHECK(list->size() == 2);
    for (const char* bad : {"10,0,20", "10,0,95,0", "nan,0,0,0", "banana"}) {
        INFO(bad);
        CHECK_FALSE(parseGeometry(bad).ok());
    }
}

TEST_CASE("histograms sum to 1 and hold no NaN over a stress grid") {
    for (double r : {1e-3, 0.1, 1.0, 10.0})
        for (double sigma : {1e-4, 0.13, 1.0})
            for (double n : {1.0, 1.5, 3.0})
                for (double ti : {0.0, 45.0, 90.0})
                    for (double tr : {0.0, 45.0, 90.0})
                        for (double dphi : {0.0, 90.0, 180.0}) {
                            SurfaceModel model{r, {0.5, 0.5, sigma, n}, 2.0};
                            for (SimulationMethod method :
                                 {SimulationMethod::Quadrature, SimulationMethod::Mc, SimulationMethod::McPaper}) {
                                auto h = simulateHistogram(model, Direction::fromDegrees(ti, dphi),
                                                           Direction::fromDegrees(tr, 0),
                                                           {.method = method, .samples = 1000, .nodes = 12});
                                double sum = 0;
                                bool finite = true;
                                for (double v : h) {
                                    sum += v;
                                    finite = finite && std::isfinite(v) && v >= 0;
                                }
                                INFO("r " << r << " sigma " << sigma << " n " << n << " " << ti << "/" << tr << "/"
                                          << dphi << " " << simulationMethodName(method));
                                REQUIRE(finite);
                                REQUIRE(std::abs(sum - 1) <= 1e-12);
                            }
                        }
}

TEST_CASE("paper Fig. 8 as behaviour: Lambertian surfaces at curet-c2") {
    const auto geometry = curetC2();
    for (SimulationMethod method : kMethods) {
        INFO(simulationMethodName(method));
        std::vector<std::vector<std::vector<double>>> byR;
        for (double r : {0.33, 0.4, 0.5, 0.6}) {
            std::vector<std::vector<double>> hs;
            for (const Geometry& g : geometry)
                hs.push_back(simulateHistogram({.roughness = r}, g.light, g.view, {.method = method}));
            for (int k = 0; k < 6; ++k) CHECK(hs[static_cast<std::size_t>(k)][0] < 0.005);  // positions 1-6
            byR.push_back(hs);
        }
        for (std::size_t i = 1; i < byR.size(); ++i) {
            for (int k = 8; k < 11; ++k)
                CHECK(byR[i][static_cast<std::size_t>(k)][0] > byR[i - 1][static_cast<std::size_t>(k)][0]);
            CHECK(stdOf(byR[i][7]) > stdOf(byR[i - 1][7]));  // position 8
        }
    }
}

TEST_CASE("paper Fig. 9 as behaviour: Torrance-Sparrow highlights peak near the specular position") {
    const auto geometry = curetC2();
    SurfaceModel foil{.roughness = 0.4, .brdf = {.kd = 0, .ks = 1, .sigma = 0.13, .ior = 1.5}, .gain = 20};
    for (SimulationMethod method : kMethods) {
        std::vector<double> bright;
        for (const Geometry& g : geometry) {
            auto h = simulateHistogram(foil, g.light, g.view, {.method = method});
            double mass = 0;
            for (std::size_t i = h.size() / 2; i < h.size(); ++i) mass += h[i];
            bright.push_back(mass);
        }
        const auto peak = static_cast<int>(std::max_element(bright.begin(), bright.end()) - bright.begin()) + 1;
        MESSAGE(std::string(simulationMethodName(method)) << ": bright-mode mass peaks at position " << peak);
        INFO(simulationMethodName(method));
        CHECK((peak >= 5 && peak <= 7));
        CHECK(bright[1] < 0.5 * bright[static_cast<std::size_t>(peak - 1)]);  // position 2
        CHECK(bright[9] < 0.5 * bright[static_cast<std::size_t>(peak - 1)]);  // position 10
    }
}

TEST_CASE("Monte Carlo converges to the quadrature like N^-1/2") {
    const auto geometry = curetC2();
    SurfaceModel plastic{.roughness = 0.4, .brdf = {.kd = 0.7, .ks = 0.3, .sigma = 0.13, .ior = 1.5}, .gain = 1.5};
    for (auto [mc, quad] : {std::pair{SimulationMethod::Mc, SimulationMethod::Quadrature},
                            std::pair{SimulationMethod::McPaper, SimulationMethod::QuadraturePaper}}) {
        double small = 0, large = 0;
        for (const Geometry& g : geometry) {
            auto reference = simulateHistogram(plastic, g.light, g.view, {.method = quad, .nodes = 256});
            auto a = simulateHistogram(plastic, g.light, g.view, {.method = mc, .samples = 4000, .seed = 3});
            auto b = simulateHistogram(plastic, g.light, g.view, {.method = mc, .samples = 256000, .seed = 4});
            small += earthMoversDistance(a, reference);
            large += earthMoversDistance(b, reference);
        }
        MESSAGE(std::string(simulationMethodName(mc))
                << ": mean EMD " << small / 11 << " at 4e3, " << large / 11 << " at 2.56e5 (ratio " << small / large
                << ", N^-1/2 predicts 8)");
        CHECK(small / large > 5);
        CHECK(small / large < 12);
    }
}

TEST_CASE("Monte Carlo results do not depend on the thread count") {
    SurfaceModel model{.roughness = 0.5};
    auto g = curetC2()[9];
    auto one =
        simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::Mc, .samples = 30000, .threads = 1});
    auto two =
        simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::Mc, .samples = 30000, .threads = 2});
    CHECK(one == two);
    auto seeded =
        simulateHistogram(model, g.light, g.view, {.method = SimulationMethod::Mc, .samples = 30000, .seed = 2});
    CHECK(seeded != one);
}

TEST_CASE("smoothing keeps the mass") {
    std::vector<double> h(64, 0.0);
    h[0] = 0.5;
    h[40] = 0.5;
    auto s = smoothHistogram(h, 2.5);
    double sum = 0;
    for (double v : s) sum += v;
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(s[40] < 0.5);
    CHECK(s[38] > 0);
}

TEST_CASE("eq. 3 is a probability density of facet normals per unit macro area") {
    // P is the slope distribution carried over to normals (d2(p, q) = dw / cos^3), so it
    // integrates to 1 over the hemisphere; the facet-area density is P / cos.
    for (double r : {0.05, 0.4, 1.5}) {
        // int P(theta) dw over the hemisphere, dw = sin(theta) dtheta dphi.
        const int n = 200000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            const double theta = (i + 0.5) / n * (std::numbers::pi / 2);
            sum += facetDensity(r, theta) * std::sin(theta);
        }
        sum *= (std::numbers::pi / 2) / n * 2 * std::numbers::pi;
        INFO("r " << r);
        CHECK(sum == doctest::Approx(1.0).epsilon(1e-6));
    }
}
