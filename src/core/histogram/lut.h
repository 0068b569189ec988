#pragma once
// Histogram-matching look-up tables (paper section 6.5).
//
// With c_ref and c_target the cumulative distributions of the reference and target grey
// values, the LUT maps v to c_target^{-1}(c_ref(v)). Both come from exact code counts, and,
// as in scikit-image's match_histograms, code k stands for the cell (k - 1, k] of values
// below it (in code units) with its pixels spread evenly over it:
//   - c_ref at a code is the mass at or below it (the top of its step), and falls linearly
//     across the code's cell; it is flat over absent codes;
//   - c_target^{-1} rises linearly across each present target code's cell and jumps over
//     absent ones, so an empty stretch of the target stays empty (scikit-image interpolates
//     across it, putting pixels where the target has none).
// So:
//   - the LUT is monotonic non-decreasing by construction;
//   - matching a distribution to itself is the identity at its codes;
//   - at the reference's codes it equals scikit-image's mapping wherever the target's codes
//     are dense, and lies in the cell (y - 1, y] of a present target code y;
//   - empty bins, spikes and single-valued images need no special cases.
//
// A plain LUT cannot split the pixels of one reference code between two target values, so
// it reproduces the target only to within the reference's largest single-code mass (about
// 0.5-1% for an 8-bit photo). Dithering removes that limit (lutInput/lutOutput below): each
// pixel's value moves to a hashed position within its code's cell before the LUT, so the
// LUT splits the code's pixels in proportion, and the output moves up half a target code
// so the cells (y - 1, y] centre on their codes. psm-rock, 64-bin L1: 0.063 -> 0.012.
// The renderer's shader uses the same hash, so CPU and GPU agree.
//
// A LUT is sampled at `entries` evenly spaced values v_k = k / (entries - 1) and read back
// with linear interpolation, exactly as a linearly filtered 1D texture of that width is.
//
//   Lut lut = matchLut(countGreyLevels(ref, mask), countGreyLevels(target, mask), 256);
//   float plain = lut.apply(grey);
//   float dithered = lutOutput(lut.apply(lutInput(grey, x, y, 1 / 765.f)), 1 / 765.f);
//
// Blending LUTs of several directions with weights w_i (summing to 1) blends their quantile
// functions: the result is the 1D Wasserstein barycentre of the targets, still monotonic.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/histogram/histogram.h"

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

/// The same from masses per code (code k at value k / (size - 1); any non-negative
/// weights with a positive sum, e.g. a model histogram).
Lut matchLut(std::span<const double> reference, std::span<const double> target, int entries);

/// The quantile function c_target^{-1} of a distribution over codes, as matchLut inverts it
/// (linear across each present code's cell, jumping over absent codes), sampled at `samples`
/// >= 2 evenly spaced probabilities u_m = m / (samples - 1). Quantile functions are what a
/// bank keeps of a target when its LUTs are made at run time (several references, regions):
/// blending them with weights blends the distributions as blending LUTs does.
std::vector<float> quantileFunction(const LevelCounts& counts, int samples);
/// The same from masses per code (any non-negative weights with a positive sum).
std::vector<float> quantileFunction(std::span<const double> mass, int samples);

/// The LUT that gives `reference` the distribution of the quantile function `quantiles`
/// (sampled as quantileFunction does; read with linear interpolation): matchLut with the
/// target given by its quantiles.
Lut matchToQuantiles(const LevelCounts& reference, std::span<const float> quantiles, int entries);

/// Dither for pixel (x, y) (and channel c), uniform in [-1/2, 1/2): a fixed integer hash,
/// reproduced bit for bit by shaders/btflut.glsl's btflutDitherOffset.
inline float ditherOffset(std::uint32_t x, std::uint32_t y, std::uint32_t c = 0) {
    std::uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ c * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return static_cast<float>(h >> 8) * (1.f / 16777216.f) - 0.5f;
}

/// Dithered LUT input: v moved to a hashed position in its code's cell [v - code, v).
/// `code` is one input code (1/765 for the grey value of 8-bit RGB). (Code 0's cell lies
/// below the LUT's range, so black reference pixels are not split.)
inline float lutInput(float v, std::uint32_t x, std::uint32_t y, float code, std::uint32_t c = 0) {
    return v + (ditherOffset(x, y, c) - 0.5f) * code;
}

/// Dithered LUT output: centres the target cells (y - 1, y] on their codes. Code 0's cell
/// lies below the range, so the LUT holds it as exactly 0, which stays black.
inline float lutOutput(float lutValue, float targetCode) {
    return lutValue > 0.f ? std::min(1.f, lutValue + 0.5f * targetCode) : 0.f;
}

/// Weighted sum of LUT value arrays of equal length: out[k] = sum_i w_i * luts[i][k].
/// Weights must be non-negative and sum to 1.
void blendLuts(std::span<const float* const> luts, std::span<const double> weights, std::size_t length, float* out);

/// True when every value is finite, in [0, 1] and non-decreasing.
bool isValidLut(const float* values, std::size_t entries);

}  // namespace btflut
