#include "core/inverse/photometric_stereo.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>

#include "core/parallel.h"

namespace btflut {

namespace {

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Solves the 3x3 system A x = b (A row-major) by its adjugate; false where A is near singular
// relative to its size (the lights span no plane).
bool solve3(const double a[9], const double b[3], double x[3]) {
    const double inv[9] = {a[4] * a[8] - a[5] * a[7], a[2] * a[7] - a[1] * a[8], a[1] * a[5] - a[2] * a[4],
                           a[5] * a[6] - a[3] * a[8], a[0] * a[8] - a[2] * a[6], a[2] * a[3] - a[0] * a[5],
                           a[3] * a[7] - a[4] * a[6], a[1] * a[6] - a[0] * a[7], a[0] * a[4] - a[1] * a[3]};
    const double det = a[0] * inv[0] + a[1] * inv[3] + a[2] * inv[6], size = a[0] + a[4] + a[8];
    if (!(std::abs(det) > 1e-6 * size * size * size)) return false;
    for (int i = 0; i < 3; ++i) x[i] = (inv[i * 3] * b[0] + inv[i * 3 + 1] * b[1] + inv[i * 3 + 2] * b[2]) / det;
    return true;
}

}  // namespace

Result<SurfaceMaps> photometricStereo(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                      const Mask& mask, const PhotometricStereoOptions& options) {
    if (images.size() != lights.size() || images.size() < 3)
        return Error{"photometric stereo needs at least three images with their lights (" +
                     std::to_string(images.size()) + " given)"};
    const Image& first = *images.front();
    std::vector<Vec3> l;
    for (Direction d : lights) {
        if (!(d.theta < std::numbers::pi / 2)) return Error{"photometric stereo: a light at or below the horizon"};
        l.push_back(toVector(d));
    }
    double span[9] = {};  // the lights' own normal matrix: do they span three directions at all?
    for (const Vec3& v : l) {
        const double c[3] = {v.x, v.y, v.z};
        for (int r = 0; r < 3; ++r)
            for (int s = 0; s < 3; ++s) span[r * 3 + s] += c[r] * c[s];
    }
    const double zero[3] = {0, 0, 0};
    double unused[3];
    if (!solve3(span, zero, unused))
        return Error{
            "photometric stereo: the lights lie in one plane through the sample (on a line of the disk), "
            "so they do not fix a normal"};
    const int channels = first.channels;
    SurfaceMaps maps{Image(first.width, first.height, 3), Image(first.width, first.height, channels), 0};
    const std::size_t n = images.size();
    const auto drop = static_cast<std::size_t>(options.shadowFraction * static_cast<double>(n));
    const auto keepTo = n - static_cast<std::size_t>(options.highlightFraction * static_cast<double>(n));
    const bool srgb = !options.linear && first.bitDepth == 8;
    std::vector<std::size_t> unresolvedRows(static_cast<std::size_t>(first.height), 0);
    parallelFor(static_cast<std::size_t>(first.height), options.threads, [&](std::size_t row) {
        const int y = static_cast<int>(row);
        std::vector<double> value(n * static_cast<std::size_t>(channels)), grey(n);
        std::vector<std::size_t> order(n);
        for (int x = 0; x < first.width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * first.width + x;
            float* normal = &maps.normals.samples[p * 3];
            float* albedo = &maps.albedo.samples[p * static_cast<std::size_t>(channels)];
            normal[0] = normal[1] = 0.5f, normal[2] = 1.f;
            std::fill(albedo, albedo + channels, 0.f);
            if (!mask.inside[p]) continue;
            for (std::size_t k = 0; k < n; ++k) {
                grey[k] = 0;
                for (int c = 0; c < channels; ++c) {
                    const double v = images[k]->samples[p * static_cast<std::size_t>(channels) + c];
                    value[k * channels + c] = srgb ? srgbToLinear(v) : v;
                    grey[k] += value[k * channels + c] / channels;
                }
            }
            // The kept samples: neither the darkest (shadows) nor the brightest (highlights).
            std::iota(order.begin(), order.end(), std::size_t{0});
            std::sort(order.begin(), order.end(),
                      [&](std::size_t a, std::size_t b) { return grey[a] != grey[b] ? grey[a] < grey[b] : a < b; });
            double a[9] = {}, b[3] = {};
            for (std::size_t r = drop; r < keepTo; ++r) {
                const std::size_t k = order[r];
                const double c[3] = {l[k].x, l[k].y, l[k].z};
                for (int i = 0; i < 3; ++i) {
                    b[i] += c[i] * grey[k];
                    for (int j = 0; j < 3; ++j) a[i * 3 + j] += c[i] * c[j];
                }
            }
            double g[3];
            const std::optional<Vec3> unit =
                keepTo >= drop + 3 && solve3(a, b, g) ? normalized({g[0], g[1], g[2]}) : std::nullopt;
            if (!unit || unit->z <= 0) {
                ++unresolvedRows[row];
                continue;
            }
            normal[0] = static_cast<float>((unit->x + 1) / 2);
            normal[1] = static_cast<float>((unit->y + 1) / 2);
            normal[2] = static_cast<float>((unit->z + 1) / 2);
            // Each channel's albedo against the fitted normal's shading over the kept samples.
            for (int c = 0; c < channels; ++c) {
                double num = 0, den = 0;
                for (std::size_t r = drop; r < keepTo; ++r) {
                    const std::size_t k = order[r];
                    const double shading = std::max(0.0, unit->x * l[k].x + unit->y * l[k].y + unit->z * l[k].z);
                    num += value[k * channels + c] * shading;
                    den += shading * shading;
                }
                albedo[c] = den > 0 ? static_cast<float>(std::clamp(num / den, 0.0, 1.0)) : 0.f;
            }
        }
    });
    maps.unresolved = std::accumulate(unresolvedRows.begin(), unresolvedRows.end(), std::size_t{0});
    return maps;
}

std::vector<double> normalAngles(const Image& a, const Image& b, const Mask& mask) {
    BTFLUT_CHECK(a.width == b.width && a.height == b.height && a.channels >= 3 && b.channels >= 3);
    BTFLUT_CHECK(mask.inside.size() == a.pixelCount());
    std::vector<double> angles;
    for (std::size_t p = 0; p < a.pixelCount(); ++p) {
        if (!mask.inside[p]) continue;
        auto unit = [p](const Image& image) {
            const float* s = &image.samples[p * static_cast<std::size_t>(image.channels)];
            return normalized({2.0 * s[0] - 1, 2.0 * s[1] - 1, 2.0 * s[2] - 1});
        };
        const std::optional<Vec3> u = unit(a), v = unit(b);
        if (!u || !v) continue;
        const double dot = std::clamp(u->x * v->x + u->y * v->y + u->z * v->z, -1.0, 1.0);
        angles.push_back(std::acos(dot) / kDegree);
    }
    std::sort(angles.begin(), angles.end());
    return angles;
}

}  // namespace btflut
