#include "core/lut.h"

#include <cmath>

namespace btflut {

namespace {

// Cumulative mass below each code: below[k] = mass of codes < k, below[size] = 1.
std::vector<double> massBelow(const LevelCounts& levels) {
    const auto total = static_cast<double>(levels.total());
    BTFLUT_CHECK(total > 0);
    std::vector<double> below(levels.counts.size() + 1, 0.0);
    std::uint64_t running = 0;
    for (std::size_t k = 0; k < levels.counts.size(); ++k) {
        running += levels.counts[k];
        below[k + 1] = static_cast<double>(running) / total;
    }
    below.back() = 1.0;
    return below;
}

}  // namespace

Lut matchLut(const LevelCounts& reference, const LevelCounts& target, int entries) {
    BTFLUT_CHECK(entries >= 2);
    const std::vector<double> refBelow = massBelow(reference);
    const std::vector<double> tgtBelow = massBelow(target);
    const auto refLast = static_cast<double>(reference.counts.size() - 1);
    const auto tgtLast = static_cast<double>(target.counts.size() - 1);
    const std::size_t tgtCodes = target.counts.size();
    Lut lut;
    lut.values.resize(static_cast<std::size_t>(entries));
    std::size_t m = 0;  // target code; only moves forward as u grows with v
    for (int e = 0; e < entries; ++e) {
        // u = c_ref(v): v's position in code units, its cell k = round(c), linear across it.
        const double c = static_cast<double>(e) / (entries - 1) * refLast + 0.5;
        const auto k = std::min(static_cast<std::size_t>(c), reference.counts.size() - 1);
        const double across = std::min(c - static_cast<double>(k), 1.0);
        const double u = std::lerp(refBelow[k], refBelow[k + 1], across);
        // c_target^{-1}(u): the first present code whose cell reaches u.
        while (m + 1 < tgtCodes && (tgtBelow[m + 1] < u || target.counts[m] == 0)) ++m;
        while (target.counts[m] == 0) --m;  // u = 1 past the last present code
        const double cellMass = tgtBelow[m + 1] - tgtBelow[m];
        const double within = std::clamp((u - tgtBelow[m]) / cellMass, 0.0, 1.0);
        const double out = (static_cast<double>(m) - 0.5 + within) / tgtLast;
        lut.values[static_cast<std::size_t>(e)] = static_cast<float>(std::clamp(out, 0.0, 1.0));
    }
    return lut;
}

void blendLuts(std::span<const float* const> luts, std::span<const double> weights,
               std::size_t length, float* out) {
    BTFLUT_CHECK(luts.size() == weights.size() && !luts.empty());
    for (std::size_t k = 0; k < length; ++k) {
        double sum = 0;
        for (std::size_t i = 0; i < luts.size(); ++i) sum += weights[i] * luts[i][k];
        out[k] = static_cast<float>(sum);
    }
}

bool isValidLut(const float* values, std::size_t entries) {
    for (std::size_t k = 0; k < entries; ++k) {
        if (!std::isfinite(values[k]) || values[k] < 0.f || values[k] > 1.f) return false;
        if (k > 0 && values[k] < values[k - 1]) return false;
    }
    return true;
}

}  // namespace btflut
