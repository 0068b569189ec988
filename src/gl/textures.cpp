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

std::vector<float> rgbSamples(const Image& image) {
    std::vector<float> rgb(image.pixelCount() * 3);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = image.samples[i * image.channels + (image.channels == 1 ? 0 : c)];
    return rgb;
}

}  // namespace btflut
