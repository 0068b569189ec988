#pragma once
// The viewer's last pass: the composite image (or two, compared with a wipe or a lens) to
// the window, with exposure and gamma (shaders/present.frag). Plain settings are a blit;
// exposure and gamma are a table of the 256 codes, made on the CPU when they change.

#include <map>
#include <string>
#include <vector>

#include "core/result.h"
#include "gl/objects.h"
#include "gl/shader.h"

namespace btflut {

struct PresentSettings {
    enum class Compare { Off, Wipe, Lens } compare = Compare::Off;
    float wipeX = 0;             ///< window pixels
    float lensX = 0, lensY = 0;  ///< window pixels, origin bottom left
    float lensRadius = 120;
    float exposure = 0;  ///< stops
    float gamma = 1;     ///< 1: none

    bool toned() const { return exposure != 0 || gamma != 1; }
};

/// One composite: its framebuffer (for the blit) and its colour texture (for the shader).
struct CompositeImage {
    GLuint framebuffer = 0, texture = 0;
};

class PresentPass {
public:
    /// Draws into the default framebuffer, `width` x `height`; `b` is read only while comparing.
    Status draw(CompositeImage a, CompositeImage b, const PresentSettings& settings, int width, int height);

private:
    std::map<std::vector<std::string>, ShaderProgram> m_programs;  ///< by defines, made when first needed
    GlVertexArray m_vertexArray;
    GlTexture m_tone;  ///< the tone table, for the exposure and gamma below
    float m_toneExposure = 0, m_toneGamma = 1;
};

}  // namespace btflut
