#include "gl/prediction_textures.h"

#include <algorithm>
#include <cmath>

#include "gl/context.h"
#include "gl/textures.h"

namespace btflut {

namespace {
std::uint8_t byteOf(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.f, 1.f) * 255.f)); }

// The predictor's planes as `export` writes them: RGBA8 layers, then the albedo's.
std::vector<std::uint8_t> planeBytes(const PredictorPlanes& planes) {
    const std::size_t texels = planes.layers.front().pixelCount(),
                      layers = planes.layers.size() + (planes.albedo.samples.empty() ? 0 : 1);
    std::vector<std::uint8_t> data(layers * texels * 4, 255);
    for (std::size_t l = 0; l < planes.layers.size(); ++l)
        std::transform(planes.layers[l].samples.begin(), planes.layers[l].samples.end(), &data[l * texels * 4], byteOf);
    if (!planes.albedo.samples.empty())
        for (std::size_t i = 0; i < texels; ++i)
            for (std::size_t c = 0; c < 3; ++c)
                data[((layers - 1) * texels + i) * 4 + c] = byteOf(planes.albedo.samples[i * 3 + c]);
    return data;
}

}  // namespace

PredictionTextures PredictionTextures::upload(const LutBank& bank, std::size_t& bytes) {
    BTFLUT_CHECK(bank.makesLuts());
    PredictionTextures t;
    t.m_bank = &bank;
    t.m_lutsAsUniforms = lutsAsUniforms(bank);
    const Predictor* predictor = t.m_predictor = &bank.predictor();
    t.m_defines = {"BLEND"};
    const std::vector<std::string> own = predictor->shaderDefines();
    t.m_defines.insert(t.m_defines.end(), own.begin(), own.end());
    if (bank.colour == ColourMode::Rgb) t.m_defines.push_back("RGB_MODE");
    // How its codes are matched (btflut.glsl's btflutMatchOf): per channel, one channel's codes,
    // or the sum of three (the grey of RGB8).
    t.m_defines.push_back(std::string("PREDICT_MATCH ") + (bank.colour == ColourMode::Rgb ? "BTFLUT_MATCH_RGB"
                                                           : predictor->codes() == 255    ? "BTFLUT_MATCH_ONE"
                                                                                          : "BTFLUT_MATCH_SUM"));
    if (bank.prediction.regions > 1) t.m_defines.push_back("REGIONS");
    if (t.m_lutsAsUniforms) t.m_defines.push_back("LUT_UNIFORMS " + std::to_string(bank.matchLength()));
    const PredictorPlanes planes = predictor->planes();
    const Image& first = planes.layers.front();
    const std::vector<std::uint8_t> data = planeBytes(planes);
    t.m_planes = uploadTextureArray(first.width, first.height, static_cast<int>(data.size() / (first.pixelCount() * 4)),
                                    4, data.data(), bytes);
    t.m_source = std::make_shared<const std::string>(predictor->shaderSource());
    if (!t.m_source->empty()) t.m_sources.push_back({predictor->name() + " decoder (generated)", *t.m_source});
    // The decoder's texture, where it is not shader source (a network past a shader's constants).
    if (!planes.network.empty() && t.m_source->empty())
        t.m_network = uploadFloatArray(planes.networkSize, 1, planes.network.data(), bytes);
    if (!bank.prediction.labels.empty())
        t.m_labels = uploadLabels(first.width, first.height, bank.prediction.labels.data(), bytes);
    return t;
}

bool lutsAsUniforms(const LutBank& bank) {
    if (!softwareRasteriser()) return false;
    const auto floats = static_cast<GLint>(bank.makesLuts() ? bank.matchLength() : bank.lutLength());
    GLint components = 0;
    gl.GetIntegerv(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS, &components);
    // A float array may take a vec4 slot per element; the other uniforms need some room too.
    return floats <= 3 * 256 && 4 * floats + 1024 <= components;
}

std::vector<GlTexture> PredictionTextures::makeLutTables() const {
    std::vector<GlTexture> tables;
    for (int c = 0; c < m_bank->channels(); ++c)
        tables.push_back(uploadLutTable(nullptr, m_bank->entries, m_bank->prediction.regions));
    return tables;
}

std::size_t PredictionTextures::lutTableBytes() const {
    return static_cast<std::size_t>(m_bank->channels()) * static_cast<std::size_t>(m_bank->entries) *
           static_cast<std::size_t>(m_bank->prediction.regions) * 4;
}

void PredictionTextures::updateLuts(const std::vector<GlTexture>& tables, const RelightFrame& frame) const {
    if (m_lutsAsUniforms) return;  // bind sets them
    const auto entries = static_cast<std::size_t>(m_bank->entries), channels = tables.size(),
               regions = static_cast<std::size_t>(m_bank->prediction.regions);
    std::vector<float> table(regions * entries);
    for (std::size_t c = 0; c < channels; ++c) {
        for (std::size_t r = 0; r < regions; ++r)
            std::copy_n(&frame.luts[(r * channels + c) * entries], entries, &table[r * entries]);
        gl.BindTexture(GL_TEXTURE_2D, tables[c].id());
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, m_bank->entries, m_bank->prediction.regions, GL_RED, GL_FLOAT,
                         table.data());
    }
}

void PredictionTextures::bind(const ShaderProgram& p, const RelightFrame& frame, const std::vector<GlTexture>& tables,
                              int first, int level) const {
    auto unit = [&](int offset, GLenum target, GLuint texture, const char* name) {
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + offset));
        gl.BindTexture(target, texture);
        gl.Uniform1i(p[name], first + offset);
    };
    unit(0, GL_TEXTURE_2D_ARRAY, m_planes.id(), "predictPlanes");
    if (level > 0 && !m_planeMipmaps) {  // made here, as Predictor::levelCodes assumes: drivers round differently
        const PredictorPlanes planes = m_predictor->planes();
        const int width = planes.layers.front().width, height = planes.layers.front().height;
        const std::vector<std::uint8_t> data = planeBytes(planes);
        const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                          layers = data.size() / (texels * 4);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (int l = 1; l < levelCount(width, height); ++l) {
            std::vector<std::uint8_t> levels;
            for (std::size_t layer = 0; layer < layers; ++layer) {
                const std::vector<std::uint8_t> one =
                    levelOfBytes(std::span(data).subspan(layer * texels * 4, texels * 4), width, height, 4, l);
                levels.insert(levels.end(), one.begin(), one.end());
            }
            gl.TexImage3D(GL_TEXTURE_2D_ARRAY, l, GL_RGBA8, levelSize(width, l), levelSize(height, l),
                          static_cast<GLsizei>(layers), 0, GL_RGBA, GL_UNSIGNED_BYTE, levels.data());
        }
        m_planeMipmaps = true;
    }
    if ((level > 0) != m_mipmapFiltered) {  // a texture whose filter takes no mipmaps has only level 0
        m_mipmapFiltered = level > 0;
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER,
                         m_mipmapFiltered ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR);
    }
    gl.Uniform1i(p["predictLevel"], level);
    if (m_labels.id()) unit(1, GL_TEXTURE_2D, m_labels.id(), "predictLabels");
    if (m_network.id()) unit(5, GL_TEXTURE_2D_ARRAY, m_network.id(), "predictNetwork");
    for (int c = 0; c < 3; ++c) {  // every sampler on a unit of its own type, even unused ones
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + 2 + c));
        gl.BindTexture(GL_TEXTURE_2D,
                       tables[std::min<std::size_t>(static_cast<std::size_t>(c), tables.size() - 1)].id());
    }
    const GLint units[3] = {first + 2, first + 3, first + 4};
    gl.Uniform1iv(p["matchLuts"], 3, units);
    const LutBank& bank = *m_bank;
    gl.Uniform1f(p["predictCodes"], static_cast<float>(m_predictor->codes()));
    gl.Uniform1i(p["matchEntries"], bank.entries);
    gl.Uniform1i(p["matchRegions"], bank.prediction.regions);
    if (m_lutsAsUniforms) gl.Uniform1fv(p["lutValues"], static_cast<GLsizei>(bank.matchLength()), frame.luts.data());
    // The predictor's frame at the light, as its shader code reads it.
    for (const ShaderValues& v : m_predictor->shaderValues(frame)) {
        const GLint location = p[v.name];
        const auto count = static_cast<GLsizei>(v.values.size() / static_cast<std::size_t>(v.size));
        if (v.integer) {
            const std::vector<GLint> integers(v.values.begin(), v.values.end());
            gl.Uniform1iv(location, count, integers.data());
        } else if (v.size == 4) {
            gl.Uniform4fv(location, count, v.values.data());
        } else if (v.size == 3) {
            gl.Uniform3fv(location, count, v.values.data());
        } else {
            gl.Uniform1fv(location, count, v.values.data());
        }
    }
}

}  // namespace btflut
