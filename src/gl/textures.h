#pragma once
// Texture uploads shared by the renderers.

#include <vector>

#include "core/image.h"
#include "gl/objects.h"

namespace btflut {

/// A LUT of `entries` floats as a 1D GL_R32F texture, linearly filtered, clamped: the
/// texture twin of Lut::applyLut.
GlTexture uploadLut(const float* values, int entries);

/// An image's samples as RGB floats (grey repeated), top row first.
std::vector<float> rgbSamples(const Image& image);

}  // namespace btflut
