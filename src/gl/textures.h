#pragma once
// Texture uploads and read-backs shared by the renderers and the viewer.

#include <vector>

#include "core/image/image.h"
#include "core/result.h"
#include "gl/objects.h"

namespace btflut {

/// A LUT of `entries` floats as a 1D GL_R32F texture, linearly filtered, clamped: the
/// texture twin of Lut::applyLut.
GlTexture uploadLut(const float* values, int entries);

/// A W x H x D LUT volume (entries along x) as a GL_R32F 3D texture, linearly filtered,
/// clamped; `values` may be null (contents set later).
GlTexture uploadLutVolume(const float* values, int entries, int height, int depth);

/// A repeating, trilinearly filtered texture with its mipmaps from `format` (GL_RGB, or
/// GL_RED for grey, read back as (v, v, v)) data of `type`, top row first; adds its GPU
/// bytes to `bytes`.
GlTexture uploadMipmapped(int width, int height, GLenum internalFormat, GLenum format, GLenum type, const void* data,
                          std::size_t& bytes);
/// An image at its own precision: R8/R16 for grey (read as RGB), RGB8/RGB16 for colour.
GlTexture uploadMipmapped(const Image& image, std::size_t& bytes);

/// Tables of LUTs: `rows` LUTs of `entries` floats as a GL_R32F 2D texture, linear along the
/// entries, clamped (a row per region of a bank that blends references); values may be null.
GlTexture uploadLutTable(const float* values, int entries, int rows);

/// Layers of 8-bit RGBA or RGB texels as a 2D array texture, no mipmaps, bilinear where a
/// shader samples it (texelFetch reads texels as they are), repeating (`layers` x width x
/// height x channels bytes, top row first); adds its bytes.
GlTexture uploadTextureArray(int width, int height, int layers, int channels, const std::uint8_t* data,
                             std::size_t& bytes);

/// Layers of RGBA32F texels (a predictor's weights or decoder), unfiltered (the shaders read
/// them with texelFetch), size x size x layers x 4 floats; adds its bytes.
GlTexture uploadFloatArray(int size, int layers, const float* data, std::size_t& bytes);

/// Per texel bytes (region labels) as an unfiltered GL_R8UI texture, read with texelFetch.
GlTexture uploadLabels(int width, int height, const std::uint8_t* data, std::size_t& bytes);

/// An empty 2D texture (a render target): `format`/`type` describe no data, only the kind.
GlTexture allocateTexture2D(int width, int height, GLenum internalFormat, GLenum format, GLenum type);

/// A render target: RGBA8 colour and a 24-bit depth buffer, attached to a framebuffer.
struct ColourDepthTarget {
    GlTexture colour, depth;
    GlFramebuffer framebuffer;
};
Result<ColourDepthTarget> allocateColourDepthTarget(int width, int height);

/// The RGBA8 colour of a framebuffer (0: the window's) as an 8-bit RGB image, top row first.
Image readFramebufferRgb(GLuint framebuffer, int width, int height);

/// An image's samples as RGB floats (grey repeated), top row first.
std::vector<float> rgbSamples(const Image& image);

}  // namespace btflut
