// The paper's inverse problems from one image's histogram: orientation (6.4, btflut orient)
// and recognition (6.3, btflut classify), on rendered height fields.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/inverse/classify.h"
#include "core/inverse/orient.h"
#include "core/inverse/photometric_stereo.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;
namespace fs = std::filesystem;

namespace {

Vec3 turned(Vec3 v, Vec3 axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle), dot = axis.x * v.x + axis.y * v.y + axis.z * v.z;
    return {v.x * c + (axis.y * v.z - axis.z * v.y) * s + axis.x * dot * (1 - c),
            v.y * c + (axis.z * v.x - axis.x * v.z) * s + axis.y * dot * (1 - c),
            v.z * c + (axis.x * v.y - axis.y * v.x) * s + axis.z * dot * (1 - c)};
}

// The synth geometry ("THETA_I,PHI_I,THETA_R,PHI_R") of a sample whose normal has (tilt,
// azimuth) in the camera's frame, lit from `light` in that frame: both turned into the
// sample's frame by the smallest rotation taking the normal to z.
std::string tiltedGeometry(Direction light, double tiltDeg, double azimuthDeg) {
    const double a = azimuthDeg * kDegree;
    const Vec3 axis{-std::sin(a), std::cos(a), 0};
    const Direction l = fromVector(turned(toVector(light), axis, -tiltDeg * kDegree));
    const Direction v = fromVector(turned({0, 0, 1}, axis, -tiltDeg * kDegree));
    char text[160];
    std::snprintf(text, sizeof text, "%.6f,%.6f,%.6f,%.6f", l.thetaDegrees(), l.phiDegrees(), v.thetaDegrees(),
                  v.phiDegrees());
    return text;
}

// Renders a Lambertian rough surface (r 0.4) at one geometry; returns the image's path.
std::string render(const TempDir& dir, const std::string& name, const std::string& geometry, int seed = 7) {
    const std::string folder = dir / name;
    CliRun run = runCli({"synth", "--roughness", "0.4", "--size", "256", "--samples", "1", "--correlation-length", "8",
                         "--seed", std::to_string(seed), "--geometry", geometry, "-q", "-o", folder});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    return folder + "/p1.png";
}

// The material's model, fitted to a calibration set (curet-c2) of another patch of it.
std::string fittedMaterial(const TempDir& dir) {
    const std::string folder = dir / "calibration";
    REQUIRE(runCli({"synth", "--roughness", "0.4", "--size", "256", "--samples", "1", "--correlation-length", "8",
                    "--geometry", "curet-c2", "-q", "-o", folder})
                .status == 0);
    REQUIRE(runCli({"fit", folder, "-o", dir / "concrete.json"}).status == 0);
    return dir / "concrete.json";
}

nlohmann::json orient(const std::string& image, const std::string& material, const std::string& flag,
                      const std::string& known) {
    CliRun run = runCli({"orient", image, "--material", material, flag, known, "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    return nlohmann::json::parse(run.out);
}

}  // namespace

TEST_CASE("orient: the tilt of rendered height fields within 5 degrees up to 60, lit from the camera") {
    TempDir dir;
    const std::string material = fittedMaterial(dir);
    for (double tilt : {0.0, 20.0, 40.0, 60.0}) {
        const std::string image = render(dir, "t" + std::to_string(static_cast<int>(tilt)),
                                         tiltedGeometry(Direction::fromDegrees(0, 0), tilt, 130));
        const nlohmann::json out = orient(image, material, "--light", "0,0");
        const nlohmann::json& best = out["candidates"][0];
        const double estimate = best["normal"]["theta"].get<double>();
        MESSAGE("tilt " << tilt << ": estimated " << estimate << " +- " << best["tilt_uncertainty"].get<double>()
                        << ", " << out["candidates"].size() << " candidate(s)");
        CHECK(std::abs(estimate - tilt) <= 5);
        CHECK(best["tilt_uncertainty"].get<double>() >= std::abs(estimate - tilt) - 1);
        // Lit from the camera, every azimuth of the normal looks the same: said, not guessed.
        if (tilt > 0) CHECK_FALSE(best["azimuth_determined"].get<bool>());
    }
    // The same sample seen from the light's side: with light and camera together, the same answer.
    const std::string image = render(dir, "v40", tiltedGeometry(Direction::fromDegrees(0, 0), 40, 130));
    CHECK(std::abs(orient(image, material, "--view", "0,0")["candidates"][0]["normal"]["theta"].get<double>() - 40) <=
          5);
}

TEST_CASE("orient: a bank with view directions as the material (light and camera together, 0 to 75 degrees)") {
    TempDir dir;
    std::string pairs;
    for (int t = 0; t < 80; t += 5)
        pairs += (pairs.empty() ? "" : ";") + std::to_string(t) + ",0," + std::to_string(t) + ",0";
    REQUIRE(runCli({"synth", "--roughness", "0.4", "--size", "256", "--samples", "1", "--correlation-length", "8",
                    "--geometry", pairs, "-q", "-o", dir / "coaxial"})
                .status == 0);
    REQUIRE(runCli({"bake", dir / "coaxial", "-o", dir / "coaxial.btflut", "-q"}).status == 0);
    for (double tilt : {30.0, 50.0}) {
        const std::string image = render(dir, "b" + std::to_string(static_cast<int>(tilt)),
                                         tiltedGeometry(Direction::fromDegrees(0, 0), tilt, 250));
        const double estimate =
            orient(image, dir / "coaxial.btflut", "--light", "0,0")["candidates"][0]["normal"]["theta"];
        MESSAGE("bank: tilt " << tilt << " estimated " << estimate);
        CHECK(std::abs(estimate - tilt) <= 5);
    }
}

TEST_CASE("orient: with the light off the camera the histogram is ambiguous; the truth is among the candidates") {
    TempDir dir;
    const std::string material = fittedMaterial(dir);
    const Direction light = Direction::fromDegrees(30, 180);
    for (auto [tilt, azimuth] : {std::pair{20.0, 0.0}, {40.0, 90.0}, {40.0, 200.0}}) {
        const std::string image =
            render(dir, "o" + std::to_string(static_cast<int>(tilt + azimuth)), tiltedGeometry(light, tilt, azimuth));
        const nlohmann::json out = orient(image, material, "--light", "30,180");
        const Direction truth = Direction::fromDegrees(tilt, azimuth);
        bool found = false;
        for (const nlohmann::json& c : out["candidates"]) {
            const Direction n =
                Direction::fromDegrees(c["normal"]["theta"].get<double>(), c["normal"]["phi"].get<double>());
            found = found || angleBetween(n, truth) / kDegree <= c["uncertainty"].get<double>() + 2;
        }
        MESSAGE("normal (" << tilt << ", " << azimuth << "): " << out["candidates"].size() << " candidate(s), best ("
                           << out["candidates"][0]["normal"]["theta"].get<double>() << ", "
                           << out["candidates"][0]["normal"]["phi"].get<double>() << ") within "
                           << out["candidates"][0]["uncertainty"].get<double>());
        CHECK(found);
    }
}

TEST_CASE("orient and classify: bad input refused with one line") {
    TempDir dir;
    const std::string image = render(dir, "img", "0,0,0,0");
    std::ofstream(dir / "p.json") << R"({"roughness": 0.4})";
    const std::string material = dir / "p.json";
    Image black(256, 256, 1);
    REQUIRE(savePng(black, dir / "empty-mask.png").ok());
    requireOneLineError(runCli({"orient", image, "--material", material, "--mask", dir / "empty-mask.png"}),
                        "no sample pixels");
    requireOneLineError(runCli({"orient", image, "--material", material, "--light", "0,0", "--view", "0,0"}),
                        "give --light or --view, not both");
    requireOneLineError(runCli({"orient", image, "--material", material, "--light", "nan,0"}), "--light");
    requireOneLineError(runCli({"orient", image, "--material", dir / "missing.json"}), "missing.json");
    requireOneLineError(runCli({"orient", image, "--material", image}), "a model's PARAMS.json or a bank's .btflut");
    requireOneLineError(runCli({"orient", dir / "none.png", "--material", material}), "none.png");
    fs::create_directories(dir / "empty");
    requireOneLineError(runCli({"classify", image, "--library", dir / "empty"}), "the library is empty");
    requireOneLineError(runCli({"classify", image, "--library", dir / "nowhere"}), "not a folder");
    fs::create_directories(dir / "lib");
    fs::copy_file(material, dir / "lib/a.json");
    requireOneLineError(runCli({"classify", image, "--library", dir / "lib", "--mask", dir / "empty-mask.png"}),
                        "no sample pixels");
    std::ofstream(dir / "lib/b.json") << "{";
    requireOneLineError(runCli({"classify", image, "--library", dir / "lib"}), "b.json");
}

TEST_CASE("classify: 8 synthetic materials, queries at lights not used to build the library: top-1 at least 90%") {
    TempDir dir;
    const std::string queries = "20,45,0,0;40,160,0,0;55,290,0,0;70,100,0,0";  // none of rti-24's lights
    const std::vector<std::pair<std::string, std::vector<std::string>>> materials{
        {"concrete", {"--preset", "concrete"}},
        {"foil", {"--preset", "foil"}},
        {"plastic", {"--preset", "plastic"}},
        {"corduroy", {"--preset", "corduroy"}},
        {"smooth", {"--roughness", "0.2"}},
        {"rough", {"--roughness", "0.7"}},
        {"dark", {"--roughness", "0.4", "--gain", "0.5"}},
        {"glossy", {"--brdf", "mix", "--kd", "0.6", "--ks", "0.4", "--roughness", "0.25"}},
    };
    fs::create_directories(dir / "library");
    std::vector<std::pair<std::string, std::string>> images;  // material, query image
    for (const auto& [name, flags] : materials) {
        auto synth = [&](const std::string& geometry, const std::string& seed, const std::string& folder) {
            std::vector<std::string> args{
                "synth", "--geometry", geometry, "--size", "256", "--samples", "1", "--correlation-length",
                "8",     "--seed",     seed,     "-q",     "-o",  folder};
            args.insert(args.end(), flags.begin(), flags.end());
            CliRun run = runCli(args);
            REQUIRE_MESSAGE(run.status == 0, run.err);
        };
        synth("rti-24", "1", dir / ("dome-" + name));
        // A predictor's bank (its measured target between the lights, which classify reads); a
        // fixed one, not auto's validated choice, which this test does not need to train.
        REQUIRE(runCli({"bake", dir / ("dome-" + name), "--predictor", "hsh2", "-o",
                        dir / ("library/" + name + ".btflut"), "-q"})
                    .status == 0);
        synth(queries, "2", dir / ("query-" + name));  // another patch of the material, under other lights
        for (int i = 1; i <= 4; ++i)
            images.push_back({name, dir / ("query-" + name + "/p" + std::to_string(i) + ".png")});
    }
    std::vector<MaterialHistograms> library;
    for (const auto& [name, flags] : materials) {
        Result<MaterialHistograms> m = loadMaterial(dir / ("library/" + name + ".btflut"));
        REQUIRE(m.ok());
        library.push_back(std::move(*m));
    }
    int right = 0, rightByMean = 0;
    for (const auto& [name, path] : images) {
        Result<Image> image = loadImage(path);
        REQUIRE(image.ok());
        const std::vector<double> h = binHistogram(countGreyLevels(*image, fullMask(image->width, image->height)), 64);
        right += library[classify(h, library, {}, Metric::Histogram).front().material].name == name;
        rightByMean += library[classify(h, library, {}, Metric::MeanBrightness).front().material].name == name;
    }
    const double accuracy = static_cast<double>(right) / images.size(),
                 baseline = static_cast<double>(rightByMean) / images.size();
    MESSAGE("top-1: histograms " << right << "/" << images.size() << ", mean brightness only " << rightByMean << "/"
                                 << images.size());
    CHECK(accuracy >= 0.9);
    CHECK(accuracy > baseline);

    // The command: top-k with scores, the right material first.
    CliRun run = runCli({"classify", images.front().second, "--library", dir / "library", "--top", "3", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json out = nlohmann::json::parse(run.out);
    REQUIRE(out["matches"].size() == 3);
    CHECK(out["matches"][0]["material"] == "concrete");
    CHECK(out["matches"][0]["score"].get<double>() <= out["matches"][1]["score"].get<double>());
}

TEST_CASE("photometric stereo: normals and albedo of a Lambertian bump, shadows and highlights left out") {
    // A bump whose normal tilts up to ~35 degrees, albedo 0.6 (R), 0.3 (G), linear images.
    const int size = 24;
    auto normalAt = [&](int x, int y) {
        const double u = (x - size / 2.0) / size, v = (y - size / 2.0) / size;
        return *normalized({-1.4 * u, 1.4 * v, 1.0});  // image rows grow downwards, y up
    };
    std::vector<Image> images;
    std::vector<Direction> lights;
    for (double phi : {0.0, 60.0, 120.0, 180.0, 240.0, 300.0})
        for (double theta : {25.0, 50.0}) lights.push_back(Direction::fromDegrees(theta, phi));
    for (Direction d : lights) {
        const Vec3 l = toVector(d);
        Image image(size, size, 2, 16);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const Vec3 n = normalAt(x, y);
                const double shading = std::max(0.0, n.x * l.x + n.y * l.y + n.z * l.z);
                image.at(x, y, 0) = static_cast<float>(0.6 * shading);
                image.at(x, y, 1) = static_cast<float>(0.3 * shading);
            }
        images.push_back(std::move(image));
    }
    images[3].at(5, 5, 0) = images[3].at(5, 5, 1) = 1.f;  // a highlight: the brightest, left out
    std::vector<const Image*> pointers;
    for (const Image& image : images) pointers.push_back(&image);
    Mask mask{size, size, std::vector<std::uint8_t>(size * size, 1)};
    mask.inside[0] = 0;
    Result<SurfaceMaps> maps = photometricStereo(pointers, lights, mask, {.linear = true});
    REQUIRE(maps.ok());
    CHECK(maps->unresolved == 0);
    Image truth(size, size, 3);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const Vec3 n = normalAt(x, y);
            truth.at(x, y, 0) = static_cast<float>((n.x + 1) / 2);
            truth.at(x, y, 1) = static_cast<float>((n.y + 1) / 2);
            truth.at(x, y, 2) = static_cast<float>((n.z + 1) / 2);
        }
    const std::vector<double> angles = normalAngles(maps->normals, truth, mask);
    REQUIRE(angles.size() == size * size - 1);
    CHECK(angles.back() < 0.5);  // the worst texel, the highlight's included
    CHECK(maps->albedo.at(12, 12, 0) == doctest::Approx(0.6).epsilon(0.01));
    CHECK(maps->albedo.at(12, 12, 1) == doctest::Approx(0.3).epsilon(0.01));
    CHECK(maps->normals.at(0, 0, 2) == 1.f);  // outside the mask: flat
    // Lights that fix no normal: all in one plane through the sample (one azimuth), or two.
    std::vector<Direction> line;
    for (double theta : {10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 15.0, 25.0, 35.0, 45.0})
        line.push_back(Direction::fromDegrees(theta, 90.0));
    CHECK(photometricStereo(pointers, line, mask, {}).error().find("lie in one plane") != std::string::npos);
    CHECK(photometricStereo({pointers[0], pointers[1]}, {lights[0], lights[1]}, mask, {})
              .error()
              .find("at least three") != std::string::npos);
    // Black images: every texel left flat and counted, nothing NaN.
    std::vector<Image> black(3, Image(4, 4, 1));
    const Mask all{4, 4, std::vector<std::uint8_t>(16, 1)};
    Result<SurfaceMaps> dark =
        photometricStereo({&black[0], &black[1], &black[2]}, {lights[0], lights[2], lights[4]}, all, {});
    REQUIRE(dark.ok());
    CHECK(dark->unresolved == 16);
    for (float s : dark->normals.samples) CHECK(std::isfinite(s));
}

TEST_CASE("btflut normals: a capture's normal map and albedo, against a true map, and bad input") {
    TempDir dir;
    const std::string material = BTFLUT_DEFAULT_MATERIAL;
    CliRun made = runCli({"normals", material, "-o", dir / "n.png", "--albedo", dir / "a.png", "--json"});
    INFO(made.err);
    REQUIRE(made.status == 0);
    const auto json = nlohmann::json::parse(made.out);
    CHECK(json["normals"] == dir / "n.png");
    CHECK(loadImage(dir / "n.png")->channels == 3);
    CHECK(loadImage(dir / "a.png").ok());
    // Its own map as the truth: no angle between them.
    CliRun same = runCli({"normals", material, "-o", dir / "m.png", "--truth", dir / "n.png", "--json"});
    REQUIRE(same.status == 0);
    CHECK(nlohmann::json::parse(same.out)["against_truth"]["p90_degrees"].get<double>() < 1.0);
    CHECK(runCli({"normals", material, "-o", dir / "x.jpg"}).err.find("-o") != std::string::npos);
    CliRun missing = runCli({"normals", material, "-o", dir / "y.png", "--truth", dir / "nothing.png"});
    CHECK(missing.status != 0);
    CHECK(missing.err.find("nothing.png") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "y.png"));  // nothing written
}
