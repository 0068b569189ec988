#pragma once
// Histogram-matching look-up tables (paper section 6.5).
//
// With c_ref and c_target the cumulative distributions of the reference and target grey
// values, the LUT maps v to c_target^{-1}(c_ref(v)). Both are taken from exact code counts:
// c at a present code is the mass at or below it (the top of its step), c_ref is linear
// between present codes, and c_target^{-1} is the quantile function linear between the
// target's present codes (scikit-image's match_histograms makes the same choices). So:
//   - the LUT is monotonic non-decreasing by construction;
//   - matching a distribution to itself gives the identity between its extreme values;
//   - at the reference's own codes it equals scikit-image's mapping exactly;
//   - empty bins, spikes and single-valued images need no special cases.
//
// A LUT is sampled at `entries` evenly spaced values v_k = k / (entries - 1) and read back
// with linear interpolation, exactly as a linearly filtered 1D texture of that width is.
//
//   Lut lut = matchLut(countGreyLevels(ref, mask), countGreyLevels(target, mask), 256);
//   float out = lut.apply(0.5f);
//
// Blending LUTs of several directions with weights w_i (summing to 1) blends their quantile
// functions: the result is the 1D Wasserstein barycentre of the targets, still monotonic.

#include <algorithm>
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

/// Weighted sum of LUT value arrays of equal length: out[k] = sum_i w_i * luts[i][k].
/// Weights must be non-negative and sum to 1.
void blendLuts(std::span<const float* const> luts, std::span<const double> weights,
               std::size_t length, float* out);

/// True when every value is finite, in [0, 1] and non-decreasing.
bool isValidLut(const float* values, std::size_t entries);

}  // namespace btflut
