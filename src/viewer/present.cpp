#include "viewer/present.h"

#include "gl/gl_api.h"
#include "gl/shader.h"

namespace btflut {

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
        Result<GlProgram> program = buildProgram({"present.vert"}, {"present.frag"}, defines);
        if (!program) return Error{program.error()};
        found = m_programs.emplace(defines, std::move(*program)).first;
    }
    if (!m_vertexArray.id()) m_vertexArray = makeVertexArray();
    const GLuint p = found->second.id();
    gl.UseProgram(p);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, a.texture);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D, s.compare == PresentSettings::Compare::Off ? a.texture : b.texture);
    gl.Uniform1i(gl.GetUniformLocation(p, "imageA"), 0);
    gl.Uniform1i(gl.GetUniformLocation(p, "imageB"), 1);
    gl.Uniform1f(gl.GetUniformLocation(p, "wipeX"), s.wipeX);
    gl.Uniform2f(gl.GetUniformLocation(p, "lensCentre"), s.lensX, s.lensY);
    gl.Uniform1f(gl.GetUniformLocation(p, "lensRadius"), s.lensRadius);
    gl.Uniform1f(gl.GetUniformLocation(p, "exposure"), s.exposure);
    gl.Uniform1f(gl.GetUniformLocation(p, "gamma"), s.gamma);
    gl.BindVertexArray(m_vertexArray.id());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
    gl.ActiveTexture(GL_TEXTURE0);
    return success();
}

}  // namespace btflut
