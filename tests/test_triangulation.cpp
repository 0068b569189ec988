#include <doctest/doctest.h>

#include <random>

#include "core/direction/triangulation.h"

using namespace btflut;

namespace {
DiskPoint combine(const Triangulation& t, const Weights& w) {
    DiskPoint p{0, 0};
    for (int i = 0; i < w.count; ++i) {
        p.x += w.weight[i] * t.points()[w.index[i]].x;
        p.y += w.weight[i] * t.points()[w.index[i]].y;
    }
    return p;
}
}  // namespace

TEST_CASE("weights reproduce nodes exactly and points inside the hull linearly") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.7, 0.7);
    std::vector<DiskPoint> pts;
    for (int i = 0; i < 40; ++i) pts.push_back({u(rng), u(rng)});
    Triangulation t(pts);
    CHECK(t.triangles().size() >= 40);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        Weights w = t.weightsAt(pts[i]);
        CHECK(w.inside);
        double own = 0;
        for (int k = 0; k < w.count; ++k)
            if (w.index[k] == static_cast<int>(i)) own += w.weight[k];
        CHECK(own == doctest::Approx(1.0).epsilon(1e-9));
    }
    for (int q = 0; q < 2000; ++q) {
        DiskPoint p{u(rng) * 1.3, u(rng) * 1.3};
        Weights w = t.weightsAt(p);
        double sum = 0;
        for (int k = 0; k < w.count; ++k) {
            CHECK(w.weight[k] >= 0);
            sum += w.weight[k];
        }
        CHECK(sum == doctest::Approx(1.0));
        if (w.inside) {  // linear precision inside: the weights rebuild the query point
            DiskPoint r = combine(t, w);
            CHECK(r.x == doctest::Approx(p.x).epsilon(1e-9));
            CHECK(r.y == doctest::Approx(p.y).epsilon(1e-9));
        }
    }
}

TEST_CASE("outside the hull the weights clamp to the nearest boundary point") {
    Triangulation t({{0, 0}, {0.5, 0}, {0, 0.5}});
    Weights w = t.weightsAt({1, 0});
    CHECK_FALSE(w.inside);
    DiskPoint r = combine(t, w);
    CHECK(r.x == doctest::Approx(0.5));
    CHECK(r.y == doctest::Approx(0.0));
}

TEST_CASE("one point and collinear points degrade gracefully") {
    Triangulation one({{0.2, 0.1}});
    Weights w = one.weightsAt({0.5, 0.5});
    CHECK(w.count == 1);
    CHECK(w.weight[0] == 1.0);
    CHECK_FALSE(w.inside);
    CHECK(one.weightsAt({0.2, 0.1}).inside);

    Triangulation line({{0.4, 0}, {0, 0}, {0.2, 0}});
    Weights mid = line.weightsAt({0.1, 0});
    CHECK(mid.inside);
    DiskPoint r = combine(line, mid);
    CHECK(r.x == doctest::Approx(0.1));
    Weights off = line.weightsAt({0.3, 0.2});
    CHECK_FALSE(off.inside);
    CHECK(combine(line, off).x == doctest::Approx(0.3));
}

TEST_CASE("rings of cocircular points (Bonn-like layouts) triangulate to cover their hull") {
    std::vector<DiskPoint> pts{{0, 0}};
    for (double theta : {15.0, 30.0, 45.0, 60.0, 75.0})
        for (int k = 0; k < 12; ++k) pts.push_back(toDisk(Direction::fromDegrees(theta, 30.0 * k)));
    Triangulation t(pts);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const double inner = std::hypot(pts.back().x, pts.back().y) * std::cos(std::numbers::pi / 12);
    for (int q = 0; q < 3000; ++q) {
        DiskPoint p{u(rng), u(rng)};
        if (std::hypot(p.x, p.y) > inner * 0.999) continue;
        REQUIRE(t.weightsAt(p).inside);
    }
}
