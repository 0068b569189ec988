#include "viewer/present.h"

#include <algorithm>
#include <cmath>

#include "gl/gl_api.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

// Each 8-bit code's value after `exposure` stops in linear light (sRGB decoded and encoded
// again) and a display `gamma` on top.
std::vector<float> toneTable(float exposure, float gamma) {
    std::vector<float> table(256);
    for (int k = 0; k < 256; ++k) {
        const double c = k / 255.0;
        const double linear = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        const double exposed = std::min(1.0, linear * std::exp2(exposure));
        const double encoded = exposed <= 0.0031308 ? exposed * 12.92 : 1.055 * std::pow(exposed, 1 / 2.4) - 0.055;
        table[static_cast<std::size_t>(k)] = static_cast<float>(std::pow(encoded, 1.0 / gamma));
    }
    return table;
}

}  // namespace

Status PresentPass::draw(CompositeImage a, CompositeImage b, const PresentSettings& s, int width, int height) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, width, height);
    if (s.compare == PresentSettings::Compare::Off && !s.toned()) {  // a copy: far cheaper on llvmpipe than a pass
        gl.BindFramebuffer(GL_READ_FRAMEBUFFER, a.framebuffer);
        gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        return success();
    }
    std::vector<std::string> defines;
    if (s.compare == PresentSettings::Compare::Wipe) defines.push_back("WIPE");
    if (s.compare == PresentSettings::Compare::Lens) defines.push_back("LENS");
    if (s.toned()) defines.push_back("TONE");
    auto found = m_programs.find(defines);
    if (found == m_programs.end()) {
        Result<ShaderProgram> program = buildProgram({"present.vert"}, {"present.frag"}, defines);
        if (!program) return Error{program.error()};
        found = m_programs.emplace(defines, std::move(*program)).first;
    }
    if (!m_vertexArray.id()) m_vertexArray = makeVertexArray();
    const ShaderProgram& p = found->second;
    gl.UseProgram(p.id());
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, a.texture);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D, s.compare == PresentSettings::Compare::Off ? a.texture : b.texture);
    gl.Uniform1i(p["imageA"], 0);
    gl.Uniform1i(p["imageB"], 1);
    gl.Uniform1f(p["wipeX"], s.wipeX);
    gl.Uniform2f(p["lensCentre"], s.lensX, s.lensY);
    gl.Uniform1f(p["lensRadius"], s.lensRadius);
    if (s.toned()) {
        if (!m_tone.id() || s.exposure != m_toneExposure || s.gamma != m_toneGamma) {
            const std::vector<float> table = toneTable(s.exposure, s.gamma);
            m_tone = uploadLut(table.data(), static_cast<int>(table.size()));
            m_toneExposure = s.exposure, m_toneGamma = s.gamma;
        }
        gl.ActiveTexture(GL_TEXTURE2);
        gl.BindTexture(GL_TEXTURE_1D, m_tone.id());
        gl.Uniform1i(p["tone"], 2);
    }
    gl.BindVertexArray(m_vertexArray.id());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
    gl.ActiveTexture(GL_TEXTURE0);
    return success();
}

}  // namespace btflut
