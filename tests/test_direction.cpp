#include <doctest/doctest.h>

#include "core/direction/direction.h"

using namespace btflut;

TEST_CASE("directions round-trip through vectors and the equal-area disk") {
    for (double theta : {0.0, 1e-6, 10.0, 45.0, 89.9})
        for (double phi : {0.0, 30.0, 181.0, 359.0}) {
            Direction d = Direction::fromDegrees(theta, phi);
            Direction v = fromVector(toVector(d));
            Direction k = fromDisk(toDisk(d));
            CHECK(angleBetween(d, v) < 1e-9);
            CHECK(angleBetween(d, k) < 1e-9);
        }
    // The horizon maps to the unit circle, the pole to the centre.
    DiskPoint h = toDisk(Direction::fromDegrees(90, 30));
    CHECK(std::hypot(h.x, h.y) == doctest::Approx(1.0));
    DiskPoint c = toDisk(Direction::fromDegrees(0, 123));
    CHECK(std::hypot(c.x, c.y) == 0.0);
}

TEST_CASE("measured light vectors: normalised within 1e-3, refused beyond, above the horizon") {
    CHECK(directionFromMeasuredVector({0, 0, 1.0005}, "x").ok());
    auto far = directionFromMeasuredVector({0, 0, 1.01}, "lights.txt:3");
    REQUIRE_FALSE(far.ok());
    CHECK(far.error().find("lights.txt:3") == 0);
    CHECK(far.error().find("not a unit vector") != std::string::npos);
    CHECK_FALSE(directionFromMeasuredVector({1, 0, 0}, "x").ok());       // horizon
    CHECK_FALSE(directionFromMeasuredVector({0, 0.6, -0.8}, "x").ok());  // below
    CHECK_FALSE(directionFromMeasuredVector({NAN, 0, 1}, "x").ok());
    CHECK(angleBetween(*directionFromMeasuredVector({0.6, 0, 0.8}, "x"),
                       Direction::fromDegrees(std::acos(0.8) / kDegree, 0)) < 1e-12);
}

TEST_CASE("THETA,PHI parsing refuses NaN, the horizon and junk") {
    auto d = parseDirection("30,45", "--light");
    REQUIRE(d.ok());
    CHECK(d->thetaDegrees() == doctest::Approx(30));
    CHECK(d->phiDegrees() == doctest::Approx(45));
    CHECK(parseDirection(" 30 , -90 ", "--light")->phiDegrees() == doctest::Approx(270));
    for (const char* bad : {"nan,0", "30", "30,", "90,0", "-1,0", "30,45,1", "abc", "30,inf"}) {
        INFO(bad);
        auto r = parseDirection(bad, "--light");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("--light") == 0);
    }
}
