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
    std::vector<std::uint8_t> data;
    if (blend.predictor == LutBank::Blend::Predictor::Ptm) {
        // The PTM's three RGB planes as three layers.
        t.m_layers = 3;
        for (int p = 0; p < 3; ++p) {
            const std::vector<std::uint8_t> plane = bank.ptm.plane(p);
            data.insert(data.end(), plane.begin(), plane.end());
        }
        t.m_references = uploadTextureArray(bank.ptm.width, bank.ptm.height, 3, 3, data.data(), bytes);
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
                        byteOf(r.samples[i * static_cast<std::size_t>(r.channels) + (r.channels == 1 ? 0 : static_cast<std::size_t>(c))]);
        }
        t.m_references = uploadTextureArray(first.width, first.height, k, 3, data.data(), bytes);
    }
    if (!blend.labels.empty()) t.m_labels = uploadLabels(first.width, first.height, blend.labels.data(), bytes);
    return t;
}

std::vector<std::string> BlendTextures::defines(const LutBank& bank) {
    std::vector<std::string> d{"BLEND"};
    if (bank.blend.predictor == LutBank::Blend::Predictor::Ptm) d.push_back("BLEND_PTM");
    if (bank.blend.predictor == LutBank::Blend::Predictor::References && bank.colour != ColourMode::Lrgb)
        d.push_back("BLEND_FETCHES " + std::to_string(std::min<std::size_t>(bank.blend.references.size(), 3)));
    if (bank.colour == ColourMode::Lrgb) {
        d.push_back("BLEND_PACKED");
        d.push_back("BLEND_LAYERS " + std::to_string((bank.blend.references.size() + 3) / 4));
    }
    if (bank.colour == ColourMode::Rgb) d.push_back("RGB_MODE");
    if (bank.blend.regions > 1) d.push_back("REGIONS");
    return d;
}

std::vector<GlTexture> BlendTextures::makeLutTables() const {
    std::vector<GlTexture> tables;
    for (int c = 0; c < m_bank->channels(); ++c) tables.push_back(uploadLutTable(nullptr, m_bank->entries, m_bank->blend.regions));
    return tables;
}

std::size_t BlendTextures::lutTableBytes() const {
    return static_cast<std::size_t>(m_bank->channels()) * static_cast<std::size_t>(m_bank->entries) *
           static_cast<std::size_t>(m_bank->blend.regions) * 4;
}

void BlendTextures::updateLuts(const std::vector<GlTexture>& tables, const RelightFrame& frame) const {
    const auto entries = static_cast<std::size_t>(m_bank->entries), channels = tables.size(),
               regions = static_cast<std::size_t>(m_bank->blend.regions);
    std::vector<float> table(regions * entries);
    for (std::size_t c = 0; c < channels; ++c) {
        for (std::size_t r = 0; r < regions; ++r)
            std::copy_n(&frame.luts[(r * channels + c) * entries], entries, &table[r * entries]);
        gl.BindTexture(GL_TEXTURE_2D, tables[c].id());
        gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, m_bank->entries, m_bank->blend.regions, GL_RED, GL_FLOAT, table.data());
    }
}

void BlendTextures::bind(GLuint p, const RelightFrame& frame, const std::vector<GlTexture>& tables, int first) const {
    auto unit = [&](int offset, GLenum target, GLuint texture, const char* name) {
        gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + offset));
        gl.BindTexture(target, texture);
        gl.Uniform1i(gl.GetUniformLocation(p, name), first + offset);
    };
    unit(0, GL_TEXTURE_2D_ARRAY, m_references.id(), "blendReferences");
    if (m_albedo.id()) unit(1, GL_TEXTURE_2D, m_albedo.id(), "blendAlbedo");
    if (m_labels.id()) unit(2, GL_TEXTURE_2D, m_labels.id(), "blendLabels");
    for (int c = 0; c < 3; ++c) {  // every sampler on a unit of its own type, even unused ones
        const std::string name = "blendLuts[" + std::to_string(c) + "]";
        unit(3 + c, GL_TEXTURE_2D, tables[std::min<std::size_t>(static_cast<std::size_t>(c), tables.size() - 1)].id(), name.c_str());
    }
    const LutBank& bank = *m_bank;
    const bool ptm = bank.blend.predictor == LutBank::Blend::Predictor::Ptm;
    const Image& reference = ptm ? bank.reference : bank.blend.references.front();
    const int codes = ptm ? 765 : reference.maxCode() * (bank.colour == ColourMode::Grey ? reference.channels : 1);
    gl.Uniform1f(gl.GetUniformLocation(p, "blendCodes"), static_cast<float>(codes));
    gl.Uniform1i(gl.GetUniformLocation(p, "blendEntries"), bank.entries);
    gl.Uniform1i(gl.GetUniformLocation(p, "blendRegions"), bank.blend.regions);
    if (ptm) {
        // As the renderer's ptm mode: the light's terms with each coefficient's scale and
        // bias folded into six weights and an offset (the CPU twin: Relighter::ptmColour).
        float weights[Ptm::kTerms];
        for (std::size_t k = 0; k < Ptm::kTerms; ++k) weights[k] = static_cast<float>(frame.ptm.weights[k]);
        gl.Uniform3fv(gl.GetUniformLocation(p, "blendPtmWeights"), 2, weights);
        gl.Uniform1f(gl.GetUniformLocation(p, "blendPtmOffset"), static_cast<float>(frame.ptm.offset));
        gl.Uniform1f(gl.GetUniformLocation(p, "blendPtmScale"), frame.ptm.scale);
    } else if (bank.colour == ColourMode::Lrgb) {
        std::vector<float> weights(static_cast<std::size_t>(m_layers) * 4, 0.f);
        for (int k = 0; k < frame.count; ++k)
            weights[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])] = static_cast<float>(frame.weights[static_cast<std::size_t>(k)]);
        gl.Uniform4fv(gl.GetUniformLocation(p, "blendWeights"), m_layers, weights.data());
    } else {
        const auto fetches = static_cast<GLsizei>(std::min<std::size_t>(bank.blend.references.size(), 3));
        GLint layers[3] = {0, 0, 0};
        float weights[3] = {0, 0, 0};
        for (int k = 0; k < frame.count; ++k) {
            layers[k] = frame.references[static_cast<std::size_t>(k)];
            weights[k] = static_cast<float>(frame.weights[static_cast<std::size_t>(k)]);
        }
        gl.Uniform1iv(gl.GetUniformLocation(p, "blendLayer"), fetches, layers);
        gl.Uniform1fv(gl.GetUniformLocation(p, "blendWeight"), fetches, weights);
    }
}


}  // namespace btflut
