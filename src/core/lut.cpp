#include "core/lut.h"

#include <cmath>

namespace btflut {

namespace {

// A monotone piecewise-linear curve through points (x_j, y_j) with strictly increasing x,
// clamped to y_0 below x_0 and to y_last above x_last.
struct Polyline {
    std::vector<double> x, y;
};

// Present codes of a distribution with their cumulative mass at the top of each step:
// (value_j, P_j) with P_last = 1.
Polyline cumulativePoints(const LevelCounts& levels) {
    const auto total = static_cast<double>(levels.total());
    BTFLUT_CHECK(total > 0);
    Polyline c;
    std::uint64_t running = 0;
    for (std::size_t k = 0; k < levels.counts.size(); ++k) {
        if (levels.counts[k] == 0) continue;
        running += levels.counts[k];
        c.x.push_back(levels.valueOf(k));
        c.y.push_back(static_cast<double>(running) / total);
    }
    c.y.back() = 1.0;  // exact, whatever the rounding of running / total
    return c;
}

}  // namespace

Lut matchLut(const LevelCounts& reference, const LevelCounts& target, int entries) {
    BTFLUT_CHECK(entries >= 2);
    const Polyline ref = cumulativePoints(reference);  // c_ref: value -> mass
    const Polyline tgt = cumulativePoints(target);     // read backwards: mass -> value
    Lut lut;
    lut.values.resize(static_cast<std::size_t>(entries));
    std::size_t r = 0, t = 0;  // both sweeps only move forward: v and c_ref(v) increase
    for (int k = 0; k < entries; ++k) {
        const double v = static_cast<double>(k) / (entries - 1);
        // u = c_ref(v)
        while (r < ref.x.size() && ref.x[r] < v) ++r;
        double u;
        if (r == 0)
            u = ref.y.front();
        else if (r == ref.x.size())
            u = 1.0;
        else if (ref.x[r] == v)
            u = ref.y[r];
        else
            u = std::lerp(ref.y[r - 1], ref.y[r], (v - ref.x[r - 1]) / (ref.x[r] - ref.x[r - 1]));
        // LUT = c_target^{-1}(u): the first present target code whose mass reaches u
        while (t < tgt.y.size() && tgt.y[t] < u) ++t;
        double out;
        if (t == 0)
            out = tgt.x.front();
        else if (t == tgt.y.size())
            out = tgt.x.back();
        else
            out = std::lerp(tgt.x[t - 1], tgt.x[t], (u - tgt.y[t - 1]) / (tgt.y[t] - tgt.y[t - 1]));
        lut.values[static_cast<std::size_t>(k)] = static_cast<float>(out);
    }
    // float rounding of neighbouring doubles cannot break order, but lerp in double can
    // wobble by an ulp where u is flat; enforce the invariant the format promises.
    for (std::size_t k = 1; k < lut.values.size(); ++k)
        lut.values[k] = std::max(lut.values[k], lut.values[k - 1]);
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
