#pragma once
// Whether a learned decoder holds btflut's 1/255 contract in half precision (issue 46: "half
// floats where the target has them, if they hold the 1/255 contract"). The decoder of
// learned_model.h computed with every value and every multiply and add rounded to IEEE
// binary16, as a shader of float16 types would (mediump in GLSL ES, min16float in HLSL); the
// frame (the light network's output and the residual's first layer at the light) is computed
// in float once per light on the CPU, as btflut does, and rounded to half as a uniform would
// be. A GPU's fused multiply-add rounds once where this rounds twice, so the figures bound
// its error from above.
//
//   HalfPrecisionError e = halfPrecisionError(model, {Direction::fromDegrees(45, 250)});
//   e.max, e.p99: in codes of 255 against the float decoder

#include <span>

#include "core/direction/direction.h"

namespace btflut {

struct LearnedModel;

struct HalfPrecisionError {
    double max = 0;  ///< largest difference from the float decoder, in codes (x 255)
    double p99 = 0;  ///< its 99th percentile over texels, channels and lights
    /// Share of texel values whose 8-bit rounding differs from the float decoder's by more than
    /// one code (the contract: at most 1/255)
    double overOneCode = 0;
};

/// The prediction of every texel at `lights`, in half precision and in float, compared.
HalfPrecisionError halfPrecisionError(const LearnedModel& model, std::span<const Direction> lights, int threads = 0);

}  // namespace btflut
