#pragma once
// Shared test helpers: temporary folders, small synthetic images, in-process CLI runs.

#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "core/image/image.h"

namespace btflut::test {

namespace fs = std::filesystem;

/// A fresh folder under the system temp dir, removed with its contents at scope exit.
class TempDir {
public:
    TempDir() {
        static int counter = 0;
        m_path =
            fs::temp_directory_path() / ("btflut-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(m_path);
        fs::create_directories(m_path);
    }
    ~TempDir() { fs::remove_all(m_path); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::string operator/(const std::string& name) const { return (m_path / name).string(); }
    const fs::path& path() const { return m_path; }

private:
    fs::path m_path;
};

/// Result of running `btflut ARGS...` in-process.
struct CliRun {
    int status;
    std::string out;
    std::string err;
};

inline CliRun runCli(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    std::streambuf* oldOut = std::cout.rdbuf(out.rdbuf());
    std::streambuf* oldErr = std::cerr.rdbuf(err.rdbuf());
    int status = cli::run(args);
    std::cout.rdbuf(oldOut);
    std::cerr.rdbuf(oldErr);
    return {status, out.str(), err.str()};
}

/// Asserts the run failed with exactly one line on stderr that contains `needle`.
inline void requireOneLineError(const CliRun& run, const std::string& needle) {
    INFO("stderr: " << run.err);
    CHECK(run.status != 0);
    CHECK(run.err.find(needle) != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

inline std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Folder of the shared measured data (../shared/data beside the project, or $BTFLUT_DATA).
/// Empty when missing; BTFLUT_REQUIRE_DATA=1 (set by .ci/run) turns that into a failure.
inline std::string sharedDataDir() {
    if (const char* env = std::getenv("BTFLUT_DATA")) return env;
    fs::path p = fs::path(BTFLUT_SOURCE_DIR) / ".." / "shared" / "data";
    return fs::exists(p) ? p.lexically_normal().string() : std::string();
}

inline bool haveSharedData(const std::string& name) {
    std::string dir = sharedDataDir();
    if (!dir.empty() && fs::exists(fs::path(dir) / name)) return true;
    if (const char* require = std::getenv("BTFLUT_REQUIRE_DATA"); require && std::string(require) == "1")
        FAIL("shared data set " << name << " not found (set BTFLUT_DATA)");
    MESSAGE("skipped: shared data set " << name << " not found");
    return false;
}

/// A grey 8-bit image of smooth random structure (every code used several times).
inline Image randomGreyImage(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    Image im(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double v = 0.5 + 0.25 * std::sin(0.21 * x + seed) * std::cos(0.17 * y) +
                       0.2 * (static_cast<double>(rng() % 1000) / 1000.0 - 0.5);
            im.at(x, y, 0) = static_cast<float>(std::lround(std::clamp(v, 0.0, 1.0) * 255) / 255.0);
        }
    return im;
}

}  // namespace btflut::test

#include <nlohmann/json.hpp>

#include "core/data/scene.h"

#include "core/bank/lut_bank.h"
#include "core/direction/direction.h"

namespace btflut::test {

inline nlohmann::json readJson(const std::string& path) { return nlohmann::json::parse(readText(path)); }

/// One image of a synthetic dataset: direction and the integer code map from the
/// reference's codes (0..99) to this image's codes, k -> offset + slope * k (injective, so
/// the exact matching LUT is known).
struct SyntheticShot {
    double thetaI, phiI, thetaR = 0, phiR = 0;
    int offset = 0, slope = 1;
};

/// Writes grey 8-bit PNGs and a btflut manifest; the first shot's image is the
/// reference image itself (offset 0, slope 1 expected). Returns the manifest path.
inline std::string writeSyntheticDataset(const TempDir& dir, const std::vector<SyntheticShot>& shots, int w = 40,
                                         int h = 30) {
    nlohmann::json manifest{{"btflut_dataset", 1}, {"images", nlohmann::json::array()}};
    for (std::size_t s = 0; s < shots.size(); ++s) {
        Image im(w, h, 1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                int code = (x * 7 + y * 13 + (x * y) % 11) % 100;  // the reference's code here
                im.at(x, y, 0) = static_cast<float>(shots[s].offset + shots[s].slope * code) / 255.f;
            }
        std::string name = "shot" + std::to_string(s) + ".png";
        REQUIRE(savePng(im, dir / name).ok());
        manifest["images"].push_back({{"file", name},
                                      {"light", {{"theta", shots[s].thetaI}, {"phi", shots[s].phiI}}},
                                      {"view", {{"theta", shots[s].thetaR}, {"phi", shots[s].phiR}}}});
    }
    std::string path = dir / "btflut-dataset.json";
    std::ofstream(path) << manifest.dump(1);
    return path;
}

/// The format version a bank is written as: 6 where validation chose a fit between the lights
/// (TFIT), else `withoutFit`.
inline std::uint32_t expectedVersion(const LutBank& bank, std::uint32_t withoutFit) {
    const bool fitted =
        std::any_of(bank.layers.begin(), bank.layers.end(), [](const ViewLayer& l) { return !l.fit.empty(); });
    return fitted ? 6 : withoutFit;
}

/// `count` lights spread over the cap up to `maxTheta` degrees (a golden-angle spiral of equal
/// solid angles, as a dome's rings).
inline std::vector<Direction> dome(int count, double maxTheta) {
    std::vector<Direction> lights;
    for (int i = 0; i < count; ++i) {
        const double t = (i + 0.5) / count;
        lights.push_back(Direction::fromDegrees(maxTheta * std::sqrt(t), std::fmod(137.5 * i, 360.0)));
    }
    return lights;
}

/// A scene whose quad (normal +z, tangent +x) fills a w x h image texel for texel under a
/// frontal camera, so each pixel centre samples one texel centre (GL tests against CPU twins).
inline Scene frontalScene(const std::string& bank, const std::string& images, int w, int h) {
    constexpr double kFov = 45;
    Scene s;
    s.file = "frontal";
    s.width = w;
    s.height = h;
    s.fovDegrees = kFov;
    s.eye = {0, 0, 1 / std::tan(kFov / 2 * M_PI / 180)};
    s.target = {0, 0, 0};
    s.up = {0, 1, 0};
    s.materials["m"] = {bank, images};
    s.quads = {{"m", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2.0 * w / h, 2, 1, RenderMode::Lut}};
    return s;
}

// A Lambertian relief under `lights`: a normal map of bumps, an albedo varying in colour,
// cast-shadow-free shading, and a black border of `border` pixels (masked out when > 0).
struct Relief {
    int size = 48, border = 0;
    bool colour = true;
};

inline Image reliefImage(const Relief& r, Direction light) {
    Image im(r.size, r.size, r.colour ? 3 : 1);
    const Vec3 l = toVector(light);
    for (int y = 0; y < r.size; ++y)
        for (int x = 0; x < r.size; ++x) {
            const bool inside = x >= r.border && y >= r.border && x < r.size - r.border && y < r.size - r.border;
            const double p = 0.6 * std::sin(0.31 * x) * std::cos(0.23 * y), q = 0.5 * std::cos(0.27 * x + 0.4 * y);
            const double norm = std::sqrt(p * p + q * q + 1);
            const double shade = std::max(0.0, (-p * l.x - q * l.y + l.z) / norm);
            for (int c = 0; c < im.channels; ++c) {
                const double albedo = 0.55 + 0.3 * std::sin(0.11 * (x + 3 * c) + 0.07 * y);
                im.at(x, y, c) =
                    inside ? static_cast<float>(std::lround(std::clamp(albedo * shade, 0.0, 1.0) * 255) / 255.0) : 0.f;
            }
        }
    return im;
}

// The relief's images as a dataset on disk (and its mask when it has a border).
inline std::string writeRelief(const TempDir& dir, const Relief& r, const std::vector<Direction>& lights) {
    nlohmann::json manifest{{"btflut_dataset", 1}, {"images", nlohmann::json::array()}};
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const std::string name = "l" + std::to_string(i) + ".png";
        REQUIRE(savePng(reliefImage(r, lights[i]), dir / name).ok());
        manifest["images"].push_back(
            {{"file", name}, {"light", {{"theta", lights[i].thetaDegrees()}, {"phi", lights[i].phiDegrees()}}}});
    }
    if (r.border > 0) {
        Image mask(r.size, r.size, 1);
        for (int y = r.border; y < r.size - r.border; ++y)
            for (int x = r.border; x < r.size - r.border; ++x) mask.at(x, y, 0) = 1;
        REQUIRE(savePng(mask, dir / "mask.png").ok());
        manifest["mask"] = "mask.png";
    }
    std::ofstream(dir / "btflut-dataset.json") << manifest.dump(1);
    return dir / "btflut-dataset.json";
}

}  // namespace btflut::test
