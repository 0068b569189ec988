#pragma once
// Histogram-matching look-up tables (paper section 6.5).
//
// With c_ref and c_target the cumulative distributions of the reference and target grey
// values, the LUT maps v to c_target^{-1}(c_ref(v)). Both come from exact code counts, each
// code standing for the cell of values that round to it (k - 1/2, k + 1/2) / (codes - 1)
// with its pixels spread evenly over that cell:
//   - c_ref rises linearly across each reference code's cell (flat over absent codes);
//   - c_target^{-1} rises linearly across each present target code's cell and jumps over
//     absent ones, so an empty stretch of the target stays empty.
// So:
//   - the LUT is monotonic non-decreasing by construction;
//   - matching a distribution to itself is the identity at its codes;
//   - a reference code maps to the target value at the middle of its quantile range,
//     within half a code of a present target code;
//   - empty bins, spikes and single-valued images need no special cases.
//
// A pure LUT cannot split the pixels of one reference code between two target values, so
// it reproduces the target only to within the reference's largest single-code mass (about
// 0.5-1% for an 8-bit photo). Dithering removes that limit: adding ditherOffset(x, y) times
// one reference code to a pixel's value before the LUT spreads each code over its cell, and
// the output histogram then equals the target's (psm-rock: 64-bin L1 0.05 -> 0.008). The
// renderer's shader uses the same hash, so CPU and GPU agree.
//
// A LUT is sampled at `entries` evenly spaced values v_k = k / (entries - 1) and read back
// with linear interpolation, exactly as a linearly filtered 1D texture of that width is.
//
//   Lut lut = matchLut(countGreyLevels(ref, mask), countGreyLevels(target, mask), 256);
//   float out = lut.apply(grey + ditherOffset(x, y) / 765.f);   // 8-bit RGB: 765 codes
//
// Blending LUTs of several directions with weights w_i (summing to 1) blends their quantile
// functions: the result is the 1D Wasserstein barycentre of the targets, still monotonic.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/histogram.h"

namespace btflut {

struct Lut {
    std::vector<float> values;  ///< LUT(k / (size - 1)), each in [0, 1], non-decreasing

    int entries() const { return static_cast<int>(values.size()); }
    /// LUT at v in [0, 1] (clamped), linear between entries.
    float apply(float v) const { return applyLut(values.data(), entries(), v); }

    static float applyLut(const float* values, int entries, float v) {
        float pos = std::clamp(v, 0.f, 1.f) * static_cast<float>(entries - 1);
        int i = std::min(static_cast<int>(pos), entries - 2);
        float t = pos - static_cast<float>(i);
        return values[i] + t * (values[i + 1] - values[i]);
    }
};

/// The matching LUT from `reference` to `target` with `entries` >= 2 samples. Both must
/// count at least one pixel.
Lut matchLut(const LevelCounts& reference, const LevelCounts& target, int entries);

/// Dither for pixel (x, y) (and channel c), uniform in [-1/2, 1/2): a fixed integer hash,
/// reproduced bit for bit by shaders/lut_common.glsl.
inline float ditherOffset(std::uint32_t x, std::uint32_t y, std::uint32_t c = 0) {
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ c * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return static_cast<float>(h >> 8) * (1.f / 16777216.f) - 0.5f;
}

/// Weighted sum of LUT value arrays of equal length: out[k] = sum_i w_i * luts[i][k].
/// Weights must be non-negative and sum to 1.
void blendLuts(std::span<const float* const> luts, std::span<const double> weights,
               std::size_t length, float* out);

/// True when every value is finite, in [0, 1] and non-decreasing.
bool isValidLut(const float* values, std::size_t entries);

}  // namespace btflut
