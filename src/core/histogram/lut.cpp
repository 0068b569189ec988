#include "core/histogram/lut.h"

#include <cmath>

namespace btflut {

namespace {

// Cumulative mass below each code: below[k] = mass of codes < k, below[size] = 1.
std::vector<double> massBelow(std::span<const double> mass) {
    double total = 0;
    for (double m : mass) total += m;
    BTFLUT_CHECK(total > 0);
    std::vector<double> below(mass.size() + 1, 0.0);
    double running = 0;
    for (std::size_t k = 0; k < mass.size(); ++k) {
        running += mass[k];
        below[k + 1] = running / total;
    }
    below.back() = 1.0;
    return below;
}

std::vector<double> asMass(const LevelCounts& levels) { return {levels.counts.begin(), levels.counts.end()}; }

// c_ref at the LUT's entries: u = c_ref(v_e) for v_e = e / (entries - 1), non-decreasing.
std::vector<double> referenceCdfAtEntries(std::span<const double> reference, int entries) {
    const std::vector<double> refBelow = massBelow(reference);
    const std::size_t refCodes = reference.size();
    const auto refLast = static_cast<double>(refCodes - 1);
    std::vector<double> u(static_cast<std::size_t>(entries));
    for (int e = 0; e < entries; ++e) {
        // v in code units lies in the cell (k - 1, k] of k = j + 1, or at the top of cell j
        // when it is exactly code j.
        const double c = static_cast<double>(e) / (entries - 1) * refLast;
        const auto j = std::min(static_cast<std::size_t>(c), refCodes - 1);
        const double frac = c - static_cast<double>(j);
        double ue = refBelow[j + 1];
        if (frac > 0 && j + 1 < refCodes) ue += (refBelow[j + 2] - refBelow[j + 1]) * frac;
        u[static_cast<std::size_t>(e)] = ue;
    }
    return u;
}

// c_target^{-1} at non-decreasing probabilities: the first present code whose mass reaches
// u, linear across that code's own cell only (the cells of absent codes get no output).
std::vector<float> inverseCdf(std::span<const double> target, const std::vector<double>& us) {
    BTFLUT_CHECK(target.size() >= 2);
    const std::vector<double> tgtBelow = massBelow(target);
    const std::size_t tgtCodes = target.size();
    const double tgtCode = 1.0 / static_cast<double>(tgtCodes - 1);
    std::vector<float> out(us.size());
    std::size_t m = 0;  // target code; only moves forward as u grows
    for (std::size_t i = 0; i < us.size(); ++i) {
        const double u = us[i];
        while (m + 1 < tgtCodes && (tgtBelow[m + 1] < u || target[m] <= 0)) ++m;
        while (target[m] <= 0) --m;  // u = 1 past the last present code
        const double top = static_cast<double>(m) / static_cast<double>(tgtCodes - 1);
        const double bottom = std::max(0.0, top - tgtCode);
        const double within = std::clamp((u - tgtBelow[m]) / (tgtBelow[m + 1] - tgtBelow[m]), 0.0, 1.0);
        out[i] = static_cast<float>(std::lerp(bottom, top, within));
    }
    return out;
}

}  // namespace

Lut matchLut(const LevelCounts& reference, const LevelCounts& target, int entries) {
    return matchLut(asMass(reference), asMass(target), entries);
}

Lut matchLut(std::span<const double> reference, std::span<const double> target, int entries) {
    BTFLUT_CHECK(entries >= 2 && reference.size() >= 2 && target.size() >= 2);
    return {inverseCdf(target, referenceCdfAtEntries(reference, entries))};
}

std::vector<float> quantileFunction(const LevelCounts& counts, int samples) {
    return quantileFunction(asMass(counts), samples);
}

std::vector<float> quantileFunction(std::span<const double> mass, int samples) {
    BTFLUT_CHECK(samples >= 2);
    std::vector<double> us(static_cast<std::size_t>(samples));
    for (int m = 0; m < samples; ++m) us[static_cast<std::size_t>(m)] = static_cast<double>(m) / (samples - 1);
    return inverseCdf(mass, us);
}

Lut matchToQuantiles(const LevelCounts& reference, std::span<const float> quantiles, int entries) {
    BTFLUT_CHECK(entries >= 2 && reference.counts.size() >= 2 && quantiles.size() >= 2);
    const std::vector<double> u = referenceCdfAtEntries(asMass(reference), entries);
    const auto last = static_cast<double>(quantiles.size() - 1);
    Lut lut;
    lut.values.resize(u.size());
    for (std::size_t e = 0; e < u.size(); ++e) {
        const double at = std::clamp(u[e], 0.0, 1.0) * last;
        const auto m = std::min(static_cast<std::size_t>(at), quantiles.size() - 2);
        lut.values[e] =
            static_cast<float>(std::lerp(double{quantiles[m]}, double{quantiles[m + 1]}, at - static_cast<double>(m)));
    }
    return lut;
}

void blendLuts(std::span<const float* const> luts, std::span<const double> weights, std::size_t length, float* out) {
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
