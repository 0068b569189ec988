#include "gl/textures.h"

namespace btflut {

GlTexture uploadLut(const float* values, int entries) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_1D, texture.id());
    gl.TexImage1D(GL_TEXTURE_1D, 0, GL_R32F, entries, 0, GL_RED, GL_FLOAT, values);
    gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    return texture;
}

GlTexture uploadLutVolume(const float* values, int entries, int height, int depth) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_3D, texture.id());
    gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, entries, height, depth, 0, GL_RED, GL_FLOAT, values);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    return texture;
}

GlTexture uploadMipmapped(int width, int height, GLenum internalFormat, GLenum format, GLenum type, const void* data,
                          std::size_t& bytes) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internalFormat), width, height, 0, format, type, data);
    gl.GenerateMipmap(GL_TEXTURE_2D);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    std::size_t texel = 4;  // drivers pad RGB to RGBA
    if (internalFormat == GL_RGB16) texel = 8;
    if (internalFormat == GL_R8) texel = 1;
    if (internalFormat == GL_R16) texel = 2;
    if (format == GL_RED) {  // grey: read as (v, v, v)
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_G, GL_RED);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_B, GL_RED);
    }
    bytes += static_cast<std::size_t>(width) * height * texel * 4 / 3;  // mipmaps add a third
    return texture;
}

GlTexture uploadMipmapped(const Image& image, std::size_t& bytes) {
    const bool sixteen = image.bitDepth == 16;
    if (image.channels == 1)
        return uploadMipmapped(image.width, image.height, sixteen ? GL_R16 : GL_R8, GL_RED, GL_FLOAT,
                               image.samples.data(), bytes);
    const std::vector<float> rgb = rgbSamples(image);
    return uploadMipmapped(image.width, image.height, sixteen ? GL_RGB16 : GL_RGB8, GL_RGB, GL_FLOAT, rgb.data(),
                           bytes);
}

GlTexture uploadLutTable(const float* values, int entries, int rows) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, entries, rows, 0, GL_RED, GL_FLOAT, values);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

GlTexture uploadTextureArray(int width, int height, int layers, int channels, const std::uint8_t* data,
                             std::size_t& bytes) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, channels == 4 ? GL_RGBA8 : GL_RGB8, width, height, layers, 0,
                  channels == 4 ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE, data);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
    bytes += static_cast<std::size_t>(width) * height * layers * 4;  // RGB padded to RGBA
    return texture;
}

GlTexture uploadFloatArray(int size, int layers, const float* data, std::size_t& bytes) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, texture.id());
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, size, size, layers, 0, GL_RGBA, GL_FLOAT, data);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    bytes += static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * static_cast<std::size_t>(layers) * 16;
    return texture;
}

GlTexture uploadLabels(int width, int height, const std::uint8_t* data, std::size_t& bytes) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, width, height, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, data);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    bytes += static_cast<std::size_t>(width) * height;
    return texture;
}

GlTexture allocateTexture2D(int width, int height, GLenum internalFormat, GLenum format, GLenum type) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internalFormat), width, height, 0, format, type, nullptr);
    return texture;
}

Result<ColourDepthTarget> allocateColourDepthTarget(int width, int height) {
    ColourDepthTarget t{allocateTexture2D(width, height, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE),
                        allocateTexture2D(width, height, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_FLOAT),
                        makeFramebuffer()};
    gl.BindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour.id(), 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t.depth.id(), 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{"the GL driver cannot render to an RGBA8 image with depth"};
    return t;
}

Image readFramebufferRgb(GLuint framebuffer, int width, int height) {
    std::vector<unsigned char> rgba(static_cast<std::size_t>(width) * height * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    Image out(width, height, 3);
    for (int row = 0; row < height; ++row)  // GL's rows run bottom up
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                out.at(x, row, c) = rgba[(static_cast<std::size_t>(height - 1 - row) * width + x) * 4 + c] / 255.f;
    return out;
}

std::vector<float> rgbSamples(const Image& image) {
    std::vector<float> rgb(image.pixelCount() * 3);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = image.samples[i * image.channels + (image.channels == 1 ? 0 : c)];
    return rgb;
}

}  // namespace btflut
