#include "gl/blend_textures.h"

#include <cmath>

#include "gl/textures.h"

namespace btflut {

namespace {
std::uint8_t byteOf(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.f, 1.f) * 255.f)); }
}  // namespace

BlendTextures BlendTextures::upload(const LutBank& bank, std::size_t& bytes) {
    BTFLUT_CHECK(bank.makesLuts());
    const LutBank::Blend& blend = bank.blend;
    const Image& first = blend.references.empty() ? bank.reference : blend.references.front();
    const auto texels = first.pixelCount();
    const auto k = static_cast<int>(blend.references.size());
    BlendTextures t;
    t.m_bank = &bank;
    t.m_lutsAsUniforms = lutsAsUniforms(bank);
    std::vector<std::uint8_t> data;
    if (bank.predictsWithModel()) {
        // The light model's 8-bit planes three to an RGB layer, its 4-bit planes six (two to a
        // channel, the first in the high nibble), then its albedo.
        const LightModel& m = blend.model;
        const auto P = static_cast<std::size_t>(m.planes), W = static_cast<std::size_t>(m.wide), n = m.texels();
        t.m_layers = (m.wide + 2) / 3;
        t.m_nibbleLayers = (m.planes - m.wide + 5) / 6;
        const auto planeLayers = static_cast<std::size_t>(t.m_layers + t.m_nibbleLayers);
        const int layers = static_cast<int>(planeLayers) + (m.albedo.empty() ? 0 : 1);
        data.assign(static_cast<std::size_t>(layers) * n * 3, 0);
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t p = 0; p < W; ++p) data[((p / 3) * n + i) * 3 + p % 3] = m.coefficients[i * P + p];
            for (std::size_t p = W; p < P; ++p) {
                const std::size_t q = p - W, layer = static_cast<std::size_t>(t.m_layers) + q / 6;
                data[(layer * n + i) * 3 + (q % 6) / 2] +=
                    static_cast<std::uint8_t>(m.coefficients[i * P + p] << (q % 2 == 0 ? 4 : 0));
            }
        }
        if (!m.albedo.empty())
            std::copy(m.albedo.begin(), m.albedo.end(),
                      data.begin() + static_cast<std::ptrdiff_t>(planeLayers * n * 3));
        t.m_references = uploadTextureArray(m.width, m.height, layers, 3, data.data(), bytes);
    } else if (bank.colour == ColourMode::Lrgb) {
        // Four grey references per RGBA layer (reference j: layer j / 4, channel j % 4).
        t.m_layers = (k + 3) / 4;
        data.assign(static_cast<std::size_t>(t.m_layers) * texels * 4, 0);
        for (int j = 0; j < k; ++j)
            for (std::size_t i = 0; i < texels; ++i)
                data[(static_cast<std::size_t>(j / 4) * texels + i) * 4 + static_cast<std::size_t>(j % 4)] =
                    byteOf(blend.references[static_cast<std::size_t>(j)].samples[i]);
        t.m_references = uploadTextureArray(first.width, first.height, t.m_layers, 4, data.data(), bytes);
        const std::vector<float> rgb = rgbSamples(blend.albedo);
        t.m_albedo = uploadMipmapped(first.width, first.height, GL_RGB8, GL_RGB, GL_FLOAT, rgb.data(), bytes);
    } else {
        t.m_layers = k;
        data.resize(static_cast<std::size_t>(k) * texels * 3);
        for (int j = 0; j < k; ++j) {
            const Image& r = blend.references[static_cast<std::size_t>(j)];
            for (std::size_t i = 0; i < texels; ++i)
                for (int c = 0; c < 3; ++c)
                    data[(static_cast<std::size_t>(j) * texels + i) * 3 + static_cast<std::size_t>(c)] =
                        byteOf(r.samples[i * static_cast<std::size_t>(r.channels) +
                                         (r.channels == 1 ? 0 : static_cast<std::size_t>(c))]);
        }
        t.m_references = uploadTextureArray(first.width, first.height, k, 3, data.data(), bytes);
    }
    if (!blend.labels.empty()) t.m_labels = uploadLabels(first.width, first.height, blend.labels.data(), bytes);
    return t;
}

bool lutsAsUniforms(const LutBank& bank) {
    const auto floats = static_cast<GLint>(bank.makesLuts() ? bank.matchLength() : bank.lutLength());
    GLint components = 0;
    gl.GetIntegerv(GL_MAX_FRAGMENT_UNIFORM_COMPONENTS, &components);
    // A float array may take a vec4 slot per element; the other uniforms need some room too.
    return floats <= 3 * 256 && 4 * floats + 1024 <= components;
}

std::vector<std::string> BlendTextures::defines(const LutBank& bank) {
    BTFLUT_CHECK(bank.makesLuts());
    std::vector<std::string> d{"BLEND"};
    if (bank.predictsWithModel()) {
        const LightModel& m = bank.blend.model;
        d.push_back("BLEND_MODEL");
        d.push_back("BLEND_MODEL_LAYERS " + std::to_string((m.wide + 2) / 3));
        d.push_back("BLEND_MODEL_NIBBLE_LAYERS " + std::to_string((m.planes - m.wide + 5) / 6));
        d.push_back("BLEND_MODEL_CHANNELS " + std::to_string(m.channels));
        if (!m.albedo.empty()) d.push_back("BLEND_MODEL_ALBEDO");
    }
    if (bank.blend.predictor == LutBank::Blend::Predictor::References && bank.colour != ColourMode::Lrgb) {
        d.push_back("BLEND_FETCHES " + std::to_string(std::min<std::size_t>(bank.blend.references.size(), 3)));
        // Grey references are uploaded in all three channels; their code is one channel's
        // (Relighter: codes 255), not the sum the grey of RGB takes.
        if (bank.blend.references.front().channels == 1) d.push_back("BLEND_GREY_REFERENCES");
    }
    if (bank.colour == ColourMode::Lrgb) {
        d.push_back("BLEND_PACKED");
        d.push_back("BLEND_LAYERS " + std::to_string((bank.blend.references.size() + 3) / 4));
    }
    if (bank.colour == ColourMode::Rgb) d.push_back("RGB_MODE");
    if (bank.blend.regions > 1) d.push_back("REGIONS");
    if (lutsAsUniforms(bank)) d.push_back("LUT_UNIFORMS " + std::to_string(bank.matchLength()));
    return d;
}

std::vector<GlTexture> BlendTextures::makeLutTables() const {
    std::vector<GlTexture> tables;
    for (int c = 0; c < m_bank->channels(); ++c)
        tables.push_back(uploadLutTable(nullptr, m_bank->entries, m_bank->blend.regions));
    return tables;
}

std::size_t BlendTextures::lutTableBytes() const {
    return static_cast<std::size_t>(m_bank->channels()) * static_cast<std::size_t>(m_bank->entries) *
           static_cast<std::size_t>(m_bank->blend.regions) * 4;
}

void BlendTextures::updateLuts(const std::vector<GlTexture>& tables, const RelightFrame& frame) const {
    if (m_lutsAsUniforms) return;  // bind sets them
    const auto entries = static_cast<std::size_t>(m_bank->entries), channels = tables.size(),
               regions = static_cast<std::size_t>(m_bank->blend.regions);
    std::vector<float> table(regions * entries);
    for (std::size_t c = 0; c < channels; ++c) {
        for (std::size_t r = 0; r < regions; ++r)
            std::copy_n(&frame.luts[(r * channels + c) * entries], entries, &table[r * entries]);
        gl.BindTexture(GL_TEXTURE_2D, tables[c].id());
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, m_bank->entries, m_bank->blend.regions, GL_RED, GL_FLOAT,
                         table.data());
    }
}

void BlendTextures::bind(const ShaderProgram& p, const RelightFrame& frame, const std::vector<GlTexture>& tables,
                         int first) const {
    auto unit = [&](int offset, GLenum target, GLuint texture, const char* name) {
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + offset));
        gl.BindTexture(target, texture);
        gl.Uniform1i(p[name], first + offset);
    };
    unit(0, GL_TEXTURE_2D_ARRAY, m_references.id(), "blendReferences");
    if (m_albedo.id()) unit(1, GL_TEXTURE_2D, m_albedo.id(), "blendAlbedo");
    if (m_labels.id()) unit(2, GL_TEXTURE_2D, m_labels.id(), "blendLabels");
    for (int c = 0; c < 3; ++c) {  // every sampler on a unit of its own type, even unused ones
        const std::string name = "blendLuts[" + std::to_string(c) + "]";
        unit(3 + c, GL_TEXTURE_2D, tables[std::min<std::size_t>(static_cast<std::size_t>(c), tables.size() - 1)].id(),
             name.c_str());
    }
    const LutBank& bank = *m_bank;
    const bool model = bank.predictsWithModel();
    gl.Uniform1f(p["blendCodes"], static_cast<float>(predictionCodes(bank)));
    gl.Uniform1i(p["blendEntries"], bank.entries);
    gl.Uniform1i(p["blendRegions"], bank.blend.regions);
    if (m_lutsAsUniforms) gl.Uniform1fv(p["lutValues"], static_cast<GLsizei>(bank.matchLength()), frame.luts.data());
    if (model) {
        // The frame's integers (LightModelFixed; the CPU twin: predictFixed), per layer of three
        // planes and per channel.
        const LightModel& m = bank.blend.model;
        const auto P = static_cast<std::size_t>(m.planes), W = static_cast<std::size_t>(m.wide),
                   C = static_cast<std::size_t>(m.channels);
        const auto layers = static_cast<std::size_t>(m_layers), nibbleLayers = static_cast<std::size_t>(m_nibbleLayers);
        std::vector<float> weights(layers * C * 3, 0.f), nibbles(nibbleLayers * C * 2 * 3, 0.f);
        for (std::size_t q = 0; q < W; ++q)
            for (std::size_t c = 0; c < C; ++c)
                weights[((q / 3) * C + c) * 3 + q % 3] = static_cast<float>(frame.model.weights[q * C + c]);
        for (std::size_t q = W; q < P; ++q)  // layer, channel, high or low nibble, then the texel's channel
            for (std::size_t c = 0; c < C; ++c) {
                const std::size_t k = q - W;
                nibbles[(((k / 6) * C + c) * 2 + k % 2) * 3 + (k % 6) / 2] =
                    static_cast<float>(frame.model.weights[q * C + c]);
            }
        if (layers > 0) gl.Uniform3fv(p["blendModelWeights"], static_cast<GLsizei>(layers * C), weights.data());
        if (nibbleLayers > 0)
            gl.Uniform3fv(p["blendModelNibbleWeights"], static_cast<GLsizei>(nibbleLayers * C * 2), nibbles.data());
        const float offset[3] = {static_cast<float>(frame.model.offset[0]), static_cast<float>(frame.model.offset[1]),
                                 static_cast<float>(frame.model.offset[2])};
        gl.Uniform3fv(p["blendModelOffset"], 1, offset);
        gl.Uniform1f(p["blendModelScale"], frame.model.scale);
    } else if (bank.colour == ColourMode::Lrgb) {
        std::vector<float> weights(static_cast<std::size_t>(m_layers) * 4, 0.f);
        for (int k = 0; k < frame.count; ++k)
            weights[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])] =
                static_cast<float>(frame.weights[static_cast<std::size_t>(k)]);
        gl.Uniform4fv(p["blendWeights"], m_layers, weights.data());
    } else {
        const auto fetches = static_cast<GLsizei>(std::min<std::size_t>(bank.blend.references.size(), 3));
        GLint layers[3] = {0, 0, 0};
        float weights[3] = {0, 0, 0};
        for (int k = 0; k < frame.count; ++k) {
            layers[k] = frame.references[static_cast<std::size_t>(k)];
            weights[k] = static_cast<float>(frame.weights[static_cast<std::size_t>(k)]);
        }
        gl.Uniform1iv(p["blendLayer"], fetches, layers);
        gl.Uniform1fv(p["blendWeight"], fetches, weights);
    }
}

}  // namespace btflut
