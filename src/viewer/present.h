#pragma once
// The viewer's last pass: the composite image (or two, compared with a wipe or a lens) to
// the window, with exposure and gamma (shaders/present.frag).

#include "core/result.h"
#include "gl/objects.h"

namespace btflut {

struct PresentSettings {
    enum class Compare { Off, Wipe, Lens } compare = Compare::Off;
    float wipeX = 0;                    ///< window pixels
    float lensX = 0, lensY = 0;         ///< window pixels, origin bottom left
    float lensRadius = 120;
    float exposure = 0;  ///< stops
    float gamma = 1;     ///< 1: none
};

class PresentPass {
public:
    static Result<PresentPass> create();
    /// Draws into the bound framebuffer's viewport; `b` is read only while comparing.
    void draw(GLuint a, GLuint b, const PresentSettings& settings) const;

private:
    GlProgram m_program;
    GlVertexArray m_vertexArray;
};

}  // namespace btflut
