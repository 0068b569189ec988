#include "core/predict/references.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace btflut {

std::vector<std::size_t> pickReferences(const std::vector<Direction>& lights, std::size_t first, std::size_t count) {
    BTFLUT_CHECK(first < lights.size() && count >= 1 && count <= lights.size());
    std::vector<std::size_t> picked{first};
    std::vector<double> distance(lights.size(), std::numeric_limits<double>::infinity());
    while (picked.size() < count) {
        const DiskPoint last = toDisk(lights[picked.back()]);
        std::size_t farthest = 0;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const DiskPoint p = toDisk(lights[i]);
            distance[i] = std::min(distance[i], std::hypot(p.x - last.x, p.y - last.y));
            if (distance[i] > distance[farthest]) farthest = i;
        }
        picked.push_back(farthest);
    }
    return picked;
}

std::vector<std::size_t> spreadLights(const std::vector<Direction>& lights, std::size_t count) {
    std::size_t frontal = 0;
    for (std::size_t i = 1; i < lights.size(); ++i)
        if (lights[i].theta < lights[frontal].theta) frontal = i;
    return pickReferences(lights, frontal, std::min(count, lights.size()));
}

namespace {

// Unit-length response of a texel (its grey values over the lights), as floats.
void feature(const Responses& r, std::size_t texel, float* out) {
    const std::uint8_t* v = &r.values[texel * static_cast<std::size_t>(r.lights)];
    double norm = 0;
    for (int k = 0; k < r.lights; ++k) norm += static_cast<double>(v[k]) * v[k];
    const float scale = norm > 0 ? static_cast<float>(1 / std::sqrt(norm)) : 0.f;
    for (int k = 0; k < r.lights; ++k) out[k] = v[k] * scale;
}

float squaredDistance(const float* a, const float* b, int n) {
    float d = 0;
    for (int k = 0; k < n; ++k) d += (a[k] - b[k]) * (a[k] - b[k]);
    return d;
}

}  // namespace

Result<Regions> segmentRegions(const Responses& responses, const Mask& mask, int count, const std::string& what) {
    BTFLUT_CHECK(count >= 1 && count <= 255);
    const std::size_t texels = static_cast<std::size_t>(responses.width) * responses.height;
    const int d = responses.lights;
    std::vector<std::size_t> inside;
    for (std::size_t i = 0; i < texels; ++i)
        if (mask.inside[i]) inside.push_back(i);
    const std::size_t minimum = std::max<std::size_t>(64, inside.size() / 100);
    if (inside.size() < minimum * static_cast<std::size_t>(count))
        return Error{what + ": " + std::to_string(inside.size()) + " sample pixels are too few for " +
                     std::to_string(count) + " regions (each needs at least " + std::to_string(minimum) + ")"};
    // Centres from at most 65536 sample texels (a fixed seed: baking is deterministic).
    std::mt19937_64 rng(20261126);
    std::vector<std::size_t> fit = inside;
    if (fit.size() > 65536) {
        std::shuffle(fit.begin(), fit.end(), rng);
        fit.resize(65536);
    }
    std::vector<float> points(fit.size() * static_cast<std::size_t>(d));
    for (std::size_t i = 0; i < fit.size(); ++i) feature(responses, fit[i], &points[i * d]);
    // k-means++: each next centre drawn with probability proportional to the squared
    // distance to the nearest chosen one.
    std::vector<float> centres(static_cast<std::size_t>(count) * d);
    std::vector<float> nearest(fit.size(), std::numeric_limits<float>::infinity());
    std::size_t pick = rng() % fit.size();
    for (int c = 0; c < count; ++c) {
        std::copy_n(&points[pick * d], d, &centres[static_cast<std::size_t>(c) * d]);
        double total = 0;
        for (std::size_t i = 0; i < fit.size(); ++i) {
            nearest[i] =
                std::min(nearest[i], squaredDistance(&points[i * d], &centres[static_cast<std::size_t>(c) * d], d));
            total += nearest[i];
        }
        double target = std::uniform_real_distribution<double>(0, total)(rng);
        for (pick = 0; pick + 1 < fit.size() && (target -= nearest[pick]) > 0; ++pick) {
        }
    }
    auto assign = [&](const float* x) {
        int best = 0;
        float bestDistance = std::numeric_limits<float>::infinity();
        for (int c = 0; c < count; ++c) {
            const float dist = squaredDistance(x, &centres[static_cast<std::size_t>(c) * d], d);
            if (dist < bestDistance) bestDistance = dist, best = c;
        }
        return best;
    };
    std::vector<int> label(fit.size(), -1);
    for (int iteration = 0; iteration < 50; ++iteration) {
        bool changed = false;
        for (std::size_t i = 0; i < fit.size(); ++i) {
            const int c = assign(&points[i * d]);
            changed = changed || c != label[i];
            label[i] = c;
        }
        if (!changed) break;
        std::vector<double> sum(centres.size(), 0.0);
        std::vector<std::size_t> members(static_cast<std::size_t>(count), 0);
        for (std::size_t i = 0; i < fit.size(); ++i) {
            ++members[static_cast<std::size_t>(label[i])];
            for (int k = 0; k < d; ++k) sum[static_cast<std::size_t>(label[i]) * d + k] += points[i * d + k];
        }
        for (int c = 0; c < count; ++c)
            if (members[static_cast<std::size_t>(c)])  // an emptied centre stays where it was
                for (int k = 0; k < d; ++k)
                    centres[static_cast<std::size_t>(c) * d + k] =
                        static_cast<float>(sum[static_cast<std::size_t>(c) * d + k] /
                                           static_cast<double>(members[static_cast<std::size_t>(c)]));
    }
    Regions regions{count, std::vector<std::uint8_t>(texels)};
    std::vector<std::size_t> members(static_cast<std::size_t>(count), 0);
    std::vector<float> x(static_cast<std::size_t>(d));
    for (std::size_t i = 0; i < texels; ++i) {
        feature(responses, i, x.data());
        regions.labels[i] = static_cast<std::uint8_t>(assign(x.data()));
        if (mask.inside[i]) ++members[regions.labels[i]];
    }
    for (int c = 0; c < count; ++c)
        if (members[static_cast<std::size_t>(c)] < minimum)
            return Error{what + ": region " + std::to_string(c) + " of " + std::to_string(count) + " holds " +
                         std::to_string(members[static_cast<std::size_t>(c)]) +
                         " sample pixels, too few for its own histograms (at least " + std::to_string(minimum) +
                         "); bake with fewer --regions"};
    return regions;
}

Result<Regions> regionsFromLabels(const Image& labels, const Mask& mask, int width, int height,
                                  const std::string& path) {
    if (labels.width != width || labels.height != height)
        return Error{path + ": label image is " + std::to_string(labels.width) + "x" + std::to_string(labels.height) +
                     " but the images are " + std::to_string(width) + "x" + std::to_string(height)};
    std::vector<int> value(labels.pixelCount());
    std::vector<int> present(65536 * 3 + 1, 0);
    for (std::size_t i = 0; i < value.size(); ++i) {
        int v = 0;
        for (int c = 0; c < labels.channels; ++c)
            v += static_cast<int>(std::lround(labels.samples[i * labels.channels + c] * labels.maxCode()));
        value[i] = v;
        present[static_cast<std::size_t>(v)] = 1;
    }
    std::vector<int> region(present.size(), 0);
    int count = 0;
    for (std::size_t v = 0; v < present.size(); ++v)
        if (present[v]) region[v] = count++;
    if (count > 255) return Error{path + ": label image has " + std::to_string(count) + " values; at most 255 regions"};
    Regions regions{count, std::vector<std::uint8_t>(value.size())};
    std::vector<std::size_t> members(static_cast<std::size_t>(count), 0);
    for (std::size_t i = 0; i < value.size(); ++i) {
        regions.labels[i] = static_cast<std::uint8_t>(region[static_cast<std::size_t>(value[i])]);
        if (mask.inside[i]) ++members[regions.labels[i]];
    }
    for (int c = 0; c < count; ++c)
        if (members[static_cast<std::size_t>(c)] == 0)
            return Error{path + ": region " + std::to_string(c) +
                         " of the label image has no sample pixels (inside the mask)"};
    return regions;
}

AlbedoAccumulator::AlbedoAccumulator(int width, int height)
    : m_width(width), m_height(height), m_sum(static_cast<std::size_t>(width) * height * 3, 0.f) {}

void AlbedoAccumulator::add(const Image& image) {
    BTFLUT_CHECK(image.width == m_width && image.height == m_height);
    std::lock_guard lock(m_mutex);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c)
            m_sum[i * 3 + c] += image.samples[i * image.channels + (image.channels == 3 ? c : 0)];
}

Image AlbedoAccumulator::finish() const {
    Image albedo(m_width, m_height, 3);
    for (std::size_t i = 0; i < albedo.pixelCount(); ++i) {
        const float top = std::max({m_sum[i * 3], m_sum[i * 3 + 1], m_sum[i * 3 + 2]});
        for (int c = 0; c < 3; ++c)
            albedo.samples[i * 3 + c] = top > 0 ? std::round(m_sum[i * 3 + c] / top * 255.f) / 255.f : 1.f;
    }
    return albedo;
}

}  // namespace btflut
