#include "gl/engine_textures.h"

#include <string>

#include "gl/gl_api.h"
#include "gl/textures.h"

namespace btflut {

namespace {

GlTexture uploadLutGrid(const EngineMaterial& m, std::size_t& bytes) {
    GlTexture texture = makeTexture();
    const auto g = static_cast<GLsizei>(m.gridSize);
    gl.BindTexture(GL_TEXTURE_3D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.TexImage3D(GL_TEXTURE_3D, 0, m.lutChannels == 3 ? GL_RGB16 : GL_R16, m.entries, g, g * m.blocks, 0,
                  m.lutChannels == 3 ? GL_RGB : GL_RED, GL_UNSIGNED_SHORT, m.lutTexels.data());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    bytes += m.lutTexels.size() * 2;
    return texture;
}

// The planes, then the albedo, as layers of one RGBA8 array.
GlTexture uploadPlanes(const EngineMaterial& m, std::size_t& bytes) {
    std::vector<const Image*> layers;
    for (const Image& image : m.images) layers.push_back(&image);
    if (!m.albedo.samples.empty()) layers.push_back(&m.albedo);
    const int width = layers.front()->width, height = layers.front()->height;
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::uint8_t> data(layers.size() * texels * 4, 255);
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const Image& image = *layers[l];
        const auto channels = static_cast<std::size_t>(image.channels);
        for (std::size_t i = 0; i < texels; ++i)
            for (std::size_t c = 0; c < channels; ++c)
                data[(l * texels + i) * 4 + c] =
                    static_cast<std::uint8_t>(image.samples[i * channels + c] * 255.f + 0.5f);
    }
    return uploadTextureArray(width, height, static_cast<int>(layers.size()), 4, data.data(), bytes);
}

// Each texel's region as R8 (region / 255), read with texelFetch; one texel of region 0 for
// a bank of one region (its sampler still needs a texture of its own type).
GlTexture uploadRegions(const Image& labels, std::size_t& bytes) {
    std::vector<std::uint8_t> data(labels.pixelCount(), 0);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(labels.samples[i] * 255.f + 0.5f);
    const int width = labels.samples.empty() ? 1 : labels.width, height = labels.samples.empty() ? 1 : labels.height;
    if (data.empty()) data.push_back(0);
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, width, height, 0, GL_RED, GL_UNSIGNED_BYTE, data.data());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    bytes += data.size();
    return texture;
}

}  // namespace

EngineTextures EngineTextures::upload(const EngineMaterial& m, std::size_t& bytes) {
    EngineTextures t;
    t.luts = uploadLutGrid(m, bytes);
    if (m.kind == PredictorKind::Luts) return t;
    t.planes = uploadPlanes(m, bytes);
    if (m.weights > 0)
        t.weights = uploadFloatArray(m.weightGridSize, m.weightLayers(), m.weightGrid.data(),
                                     bytes);  // btflutWeightLayer filters exactly
    t.labels = uploadRegions(m.labels, bytes);
    return t;
}

void EngineTextures::bind(const ShaderProgram& program, const EngineMaterial& m, int first) const {
    auto location = [&](std::string_view name) { return program[name]; };
    auto unit = [&](int k, GLenum target, const GlTexture& texture, const char* name) {
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + k));
        gl.BindTexture(target, texture.id());
        gl.Uniform1i(location(name), first + k);
    };
    unit(0, GL_TEXTURE_3D, luts, "luts");
    if (m.kind == PredictorKind::Luts) return;
    unit(1, GL_TEXTURE_2D_ARRAY, planes, "planes");
    unit(2, GL_TEXTURE_2D_ARRAY, weights, "weights");  // none for ptm, hsh: never read
    unit(3, GL_TEXTURE_2D, labels, "labels");
    gl.Uniform1i(location("predictor.kind"), m.predictorKind());
    gl.Uniform1i(location("predictor.basis"), static_cast<int>(m.basis));
    gl.Uniform1i(location("predictor.order"), m.order);
    gl.Uniform1i(location("predictor.planes"), m.planes);
    gl.Uniform1i(location("predictor.channels"), m.channels);
    gl.Uniform1i(location("predictor.albedo"), m.albedo.samples.empty() ? 0 : m.albedoMultiplies ? 1 : 2);
    if (!m.scale.empty()) {
        gl.Uniform1fv(location("predictor.scale"), static_cast<GLsizei>(m.scale.size()), m.scale.data());
        gl.Uniform1fv(location("predictor.bias"), static_cast<GLsizei>(m.bias.size()), m.bias.data());
    }
    gl.Uniform1i(location("predictor.regions"), m.regions);
    gl.Uniform1f(location("predictor.codes"), static_cast<float>(m.codes));
    gl.Uniform1i(location("predictor.rgbLuts"), m.colour == ColourMode::Rgb ? 1 : 0);
    gl.Uniform1i(location("predictor.greyOutput"), m.outputChannels == 1 ? 1 : 0);
    gl.Uniform1f(location("predictor.outputCode"), m.outputCode);
    gl.Uniform1i(location("predictor.dither"), 1);
}

}  // namespace btflut
