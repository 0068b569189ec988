#include "viewer/present.h"

#include "gl/gl_api.h"
#include "gl/shader.h"

namespace btflut {

Result<PresentPass> PresentPass::create() {
    Result<GlProgram> program = buildProgram({"present.vert"}, {"present.frag"}, {});
    if (!program) return Error{program.error()};
    PresentPass pass;
    pass.m_program = std::move(*program);
    pass.m_vertexArray = makeVertexArray();
    return pass;
}

void PresentPass::draw(GLuint a, GLuint b, const PresentSettings& s) const {
    const GLuint p = m_program.id();
    gl.UseProgram(p);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, a);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D, s.compare == PresentSettings::Compare::Off ? a : b);
    gl.Uniform1i(gl.GetUniformLocation(p, "imageA"), 0);
    gl.Uniform1i(gl.GetUniformLocation(p, "imageB"), 1);
    gl.Uniform1i(gl.GetUniformLocation(p, "compareMode"), static_cast<int>(s.compare));
    gl.Uniform1f(gl.GetUniformLocation(p, "wipeX"), s.wipeX);
    gl.Uniform2f(gl.GetUniformLocation(p, "lensCentre"), s.lensX, s.lensY);
    gl.Uniform1f(gl.GetUniformLocation(p, "lensRadius"), s.lensRadius);
    gl.Uniform1f(gl.GetUniformLocation(p, "exposure"), s.exposure);
    gl.Uniform1f(gl.GetUniformLocation(p, "gamma"), s.gamma);
    gl.BindVertexArray(m_vertexArray.id());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
    gl.ActiveTexture(GL_TEXTURE0);
}

}  // namespace btflut
