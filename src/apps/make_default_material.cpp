// Makes btflut's bundled default material: a small multi-light image set of a shaded,
// self-shadowing rough height field with a two-tone albedo, written as PNGs with a btflut
// manifest and an RTI .lp file. Deterministic (fixed seed, integer RNG), run at build time.
//
//   btflut_make_default_material OUTPUT_FOLDER

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>

#include "core/direction.h"
#include "core/image.h"

using namespace btflut;

namespace {

constexpr int kSize = 256;

// A smooth periodic random field: white noise blurred by repeated box filters.
std::vector<double> smoothNoise(std::mt19937& rng, int radius, int passes) {
    std::vector<double> f(kSize * kSize), tmp(f.size());
    // Top 53 bits of the generator's output: identical on every platform, unlike
    // std::uniform_real_distribution.
    for (double& v : f) v = static_cast<double>(rng() >> 5) / static_cast<double>(1u << 27) - 0.5;
    auto at = [](int x, int y) { return ((y + kSize) % kSize) * kSize + (x + kSize) % kSize; };
    for (int p = 0; p < passes; ++p) {
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                double s = 0;
                for (int d = -radius; d <= radius; ++d) s += f[at(x + d, y)];
                tmp[at(x, y)] = s / (2 * radius + 1);
            }
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                double s = 0;
                for (int d = -radius; d <= radius; ++d) s += tmp[at(x, y + d)];
                f[at(x, y)] = s / (2 * radius + 1);
            }
    }
    return f;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s OUTPUT_FOLDER\n", argv[0]);
        return 2;
    }
    const std::filesystem::path folder = argv[1];
    std::filesystem::create_directories(folder);
    std::mt19937 rng(20261121u);

    // Height in pixel units: coarse bumps plus finer grain, scaled to an rms slope of ~0.45.
    std::vector<double> coarse = smoothNoise(rng, 6, 3), fine = smoothNoise(rng, 2, 2),
                        tone = smoothNoise(rng, 8, 3);
    std::vector<double> h(coarse.size());
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = coarse[i] + 0.35 * fine[i];
    auto at = [](int x, int row) { return ((row + kSize) % kSize) * kSize + (x + kSize) % kSize; };
    double slope2 = 0;
    for (int row = 0; row < kSize; ++row)
        for (int x = 0; x < kSize; ++x) {
            double dx = 0.5 * (h[at(x + 1, row)] - h[at(x - 1, row)]);
            slope2 += dx * dx;
        }
    const double scale = 0.45 / std::sqrt(slope2 / (kSize * kSize));
    for (double& v : h) v *= scale;
    double toneRms = 0;
    for (double v : tone) toneRms += v * v;
    toneRms = std::sqrt(toneRms / static_cast<double>(tone.size()));

    // Lights: frontal, then rings at 20, 40 and 60 degrees, 8 azimuths each.
    std::vector<Direction> lights{Direction::fromDegrees(0, 0)};
    for (double theta : {20.0, 40.0, 60.0})
        for (int k = 0; k < 8; ++k) lights.push_back(Direction::fromDegrees(theta, 45.0 * k + theta / 4));

    nlohmann::json manifest{{"btflut_dataset", 1}, {"images", nlohmann::json::array()}};
    std::string lp = std::to_string(lights.size()) + "\n";
    for (std::size_t n = 0; n < lights.size(); ++n) {
        const Vec3 l = toVector(lights[n]);
        const double cotTheta = l.z / std::hypot(l.x, l.y);
        Image image(kSize, kSize, 3);
        for (int row = 0; row < kSize; ++row)
            for (int x = 0; x < kSize; ++x) {
                // Image y points up, so the row above (row - 1) is +y.
                double dx = 0.5 * (h[at(x + 1, row)] - h[at(x - 1, row)]);
                double dy = 0.5 * (h[at(x, row - 1)] - h[at(x, row + 1)]);
                double len = std::sqrt(dx * dx + dy * dy + 1);
                double cosine = std::max(0.0, (-dx * l.x - dy * l.y + l.z) / len);
                // Cast shadow: march towards the light; blocked if the field rises above the ray.
                bool lit = cosine > 0;
                if (lit && lights[n].theta > 1e-6)
                    for (double t = 1; t < 96 && lit; t += 1) {
                        double px = x + t * l.x / std::hypot(l.x, l.y);
                        double py = row - t * l.y / std::hypot(l.x, l.y);
                        double ray = h[at(x, row)] + t * cotTheta;
                        lit = h[at(static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py)))] <= ray;
                    }
                double mix = 0.5 + 0.5 * std::tanh(2.5 * tone[at(x, row)] / toneRms);
                const double albedo[3] = {0.80 - 0.25 * mix, 0.72 - 0.22 * mix, 0.58 - 0.12 * mix};
                double radiance = lit ? 0.95 * cosine : 0.0;
                for (int c = 0; c < 3; ++c)
                    image.at(x, row, c) = static_cast<float>(std::min(1.0, albedo[c] * radiance + 0.02));
            }
        std::string name = "default." + std::to_string(n) + ".png";
        if (Status s = savePng(image, (folder / name).string()); !s) {
            std::fprintf(stderr, "%s\n", s.error().c_str());
            return 1;
        }
        manifest["images"].push_back({{"file", name},
                                      {"light", {{"theta", lights[n].thetaDegrees()}, {"phi", lights[n].phiDegrees()}}}});
        char line[128];
        std::snprintf(line, sizeof line, "%s %.9f %.9f %.9f\n", name.c_str(), l.x, l.y, l.z);
        lp += line;
    }
    if (Status s = writeFileAtomically((folder / "default.lp").string(), lp); !s) return 1;
    if (Status s = writeFileAtomically((folder / "btflut-dataset.json").string(), manifest.dump(1) + "\n"); !s)
        return 1;
    return 0;
}
