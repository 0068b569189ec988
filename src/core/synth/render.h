#pragma once
// Renders a height field as an orthographic camera sees it under a collimated light: the
// ground truth the histogram model is compared with.
//
//   Image img = renderHeightField(field, model, light, view, {.samplesPerAxis = 2});
//
// Pixel (i, row) is the ray that crosses the mean plane at x = i + 1/2, y = size - row - 1/2
// (image y up), so every pixel covers the same image area whatever the view. Each ray is
// marched from above the field to its first hit (masking); the hit is shadowed when it faces
// away from the light or the field rises above the ray towards the light (cast shadows). Lit
// hits take the local BRDF's radiance (facetRadiance, the model's); a pixel averages s x s
// sub-rays and the camera then clips at 1.

#include <cstdint>
#include <vector>

#include "core/image/image.h"
#include "core/physics/surface.h"
#include "core/synth/height_field.h"

namespace btflut {

struct RenderOptions {
    int samplesPerAxis = 2;  ///< s: s x s rays per pixel
    int threads = 0;         ///< 0: all cores
    /// Surface albedo per field pixel (size x size, in [0, 1]); empty: 1 everywhere.
    const std::vector<double>* albedo = nullptr;
    double ambient = 0;  ///< constant diffuse irradiance (interreflection, sky), lit or not
    double noise = 0;    ///< sensor noise: standard deviation per pixel, before clipping
    std::uint64_t noiseSeed = 1;
};

/// A grey image (field.size x field.size), values in [0, 1]. The albedo scales the local
/// BRDF; the ambient term adds ambient * albedo * kd to every hit; noise is reproducible
/// from its seed whatever the thread count.
Image renderHeightField(const HeightField& field, const SurfaceModel& model, Direction light, Direction view,
                        const RenderOptions& options);

}  // namespace btflut
