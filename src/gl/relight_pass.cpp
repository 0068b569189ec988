#include "gl/relight_pass.h"

#include "gl/gl_api.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

std::vector<std::string> mapsReferenceDefines(const LutBank& bank) {
    std::vector<std::string> defines{"MAPS_REFERENCE"};
    if (bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
    if (lutsAsUniforms(bank)) defines.push_back("LUT_UNIFORMS " + std::to_string(bank.lutLength()));
    return defines;
}

RelightPass::RelightPass(const LutBank& bank, GLuint reference, const PredictionTextures* prediction)
    : m_bank(&bank),
      m_lutsAsUniforms(lutsAsUniforms(bank)),
      m_reference(reference),
      m_prediction(prediction),
      m_defines(prediction ? prediction->defines() : mapsReferenceDefines(bank)) {
    BTFLUT_CHECK(bank.makesLuts() == (prediction != nullptr));
    m_framebuffer = makeFramebuffer();
    m_vertexArray = makeVertexArray();
}

std::vector<GlTexture> RelightPass::makeLuts() const {
    if (m_prediction) return m_prediction->makeLutTables();
    std::vector<GlTexture> luts;
    for (int c = 0; c < m_bank->channels(); ++c) luts.push_back(uploadLut(nullptr, m_bank->entries));
    return luts;
}

std::size_t RelightPass::lutBytes() const {
    if (m_prediction) return m_prediction->lutTableBytes();
    return static_cast<std::size_t>(m_bank->channels()) * static_cast<std::size_t>(m_bank->entries) * 4;
}

Result<const ShaderProgram*> RelightPass::program(bool dither) {
    auto found = m_programs.find(dither);
    if (found == m_programs.end()) {
        std::vector<std::string> defines = m_defines;
        if (dither) defines.push_back("DITHER");
        Result<ShaderProgram> p =
            buildProgram({"quad.vert"}, {"btflut.glsl", "lut_common.glsl", "native.frag"}, defines, sources());
        if (!p) return Error{p.error()};
        found = m_programs.emplace(dither, std::move(*p)).first;
    }
    return &found->second;
}

const std::vector<ShaderFile>& RelightPass::sources() const {
    static const std::vector<ShaderFile> none;
    return m_prediction ? m_prediction->sources() : none;
}

void RelightPass::uploadLuts(const RelightFrame& frame, const std::vector<GlTexture>& luts) const {
    if (m_prediction) {
        m_prediction->updateLuts(luts, frame);
        return;
    }
    if (m_lutsAsUniforms) return;  // bindLuts sets them
    for (std::size_t c = 0; c < luts.size(); ++c) {
        gl.BindTexture(GL_TEXTURE_1D, luts[c].id());
        gl.TexSubImage1D(GL_TEXTURE_1D, 0, 0, m_bank->entries, GL_RED, GL_FLOAT,
                         &frame.luts[c * static_cast<std::size_t>(m_bank->entries)]);
    }
}

void RelightPass::bindLuts(const ShaderProgram& p, const RelightFrame& frame, const std::vector<GlTexture>& luts,
                           int first, int level) const {
    const LutBank& bank = *m_bank;
    BTFLUT_CHECK(level == 0 || m_prediction);
    if (m_prediction) {
        m_prediction->bind(p, frame, luts, first, level);
    } else if (m_lutsAsUniforms) {
        gl.Uniform1fv(p["lutValues"], static_cast<GLsizei>(bank.lutLength()), frame.luts.data());
    } else {
        for (int c = 0; c < 3; ++c) {  // every sampler on a unit of its own type, even unused ones
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + c));
            gl.BindTexture(GL_TEXTURE_1D, luts[static_cast<std::size_t>(std::min(c, bank.channels() - 1))].id());
        }
        const GLint units[3] = {first, first + 1, first + 2};
        gl.Uniform1iv(p["lut"], 3, units);  // the array from its first element (GL ignores unused ones)
    }
    if (!m_prediction) {
        gl.Uniform1i(p["entries"], bank.entries);
        gl.Uniform1f(p["inCode"], inputCode(bank.reference, bank.colour));
    }
    gl.Uniform1f(p["outCode"], bank.targetCode());
}

Status RelightPass::run(const RelightFrame& frame, const std::vector<GlTexture>& luts, GLuint target, bool dither,
                        int level, const std::optional<TexelRegion>& region) {
    const Image& ref = m_bank->reference;
    Result<const ShaderProgram*> program = this->program(dither);
    if (!program) return Error{program.error()};
    const ShaderProgram& p = **program;
    uploadLuts(frame, luts);
    gl.BindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, level);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{"the GL driver cannot render into the relit texture's format"};
    gl.UseProgram(p.id());
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, m_reference);
    gl.Uniform1i(p["reference"], 0);
    bindLuts(p, frame, luts, m_prediction ? 4 : 1, level);
    gl.Uniform1i(p["referenceChannels"], ref.channels);
    gl.BindVertexArray(m_vertexArray.id());
    gl.Disable(GL_DEPTH_TEST);
    const int width = levelSize(ref.width, level), height = levelSize(ref.height, level);
    gl.Viewport(0, 0, width, height);
    if (!region || region->isWhole()) {
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        return success();
    }
    gl.Enable(GL_SCISSOR_TEST);  // image row r is the target's row r (uploadMipmapped), so rows need no flip
    for (const auto& [x, y, w, h] : region->rectsAt(width, height)) {
        gl.Scissor(x, y, w, h);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl.Disable(GL_SCISSOR_TEST);
    return success();
}

GlTexture allocateRelitTexture(const Image& reference) {
    const bool grey = reference.channels == 1, sixteen = reference.bitDepth == 16;
    const GLenum format = grey ? (sixteen ? GL_R16 : GL_R8) : (sixteen ? GL_RGBA16 : GL_RGBA8);
    GlTexture texture =
        allocateTexture2D(reference.width, reference.height, format, grey ? GL_RED : GL_RGBA, GL_UNSIGNED_BYTE);
    gl.GenerateMipmap(GL_TEXTURE_2D);  // allocates the chain
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (grey) {
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_G, GL_RED);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_B, GL_RED);
    }
    return texture;
}

std::size_t relitTextureBytes(const Image& reference) {
    const std::size_t texel = (reference.channels == 1 ? 1 : 4) * (reference.bitDepth == 16 ? 2 : 1);
    return reference.pixelCount() * texel * 4 / 3;
}

}  // namespace btflut
