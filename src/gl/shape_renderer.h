#pragma once
// A material on a sphere or a cylinder (shaders/shape.vert, shape.frag): each fragment takes
// the light and view directions in its own tangent frame and the LUT for them from the bank's
// grid (one trilinear fetch, as shaders/btflut.glsl does in an engine), so light and view vary
// across the surface. A directional or a point light. Every kind of bank, drawn as an engine
// draws its export (EngineMaterial, EngineTextures, btflut.glsl's btflutRelight): for a bank
// with a predictor (a light model, or references blended) the predictor's weights at each
// fragment's light (closed form, or read from a grid over the light disk), its planes or
// references bilinearly at the texel, and the match LUT from the bank's match grid at that
// light (per region). Where the bank's mask leaves background in the image, the shape wraps the
// mask's largest rectangle (sampleWindow), tiled mirrored, as the web page's sphere does.
//
//   Result<std::unique_ptr<ShapeRenderer>> r = ShapeRenderer::create("rock.btflut");
//   (*r)->draw({Shape::Sphere, eye, target, up, 40, light}, 800, 600);   // then read framebuffer()

#include <memory>
#include <optional>

#include "core/bank/lut_bank.h"
#include "core/data/scene.h"
#include "core/relight/engine_material.h"
#include "core/result.h"
#include "gl/engine_textures.h"
#include "gl/objects.h"
#include "gl/textures.h"

namespace btflut {

enum class Shape { Sphere, Cylinder };

struct ShapeLight {
    bool point = false;
    Vec3 direction{0, 0, 1};  ///< directional: towards the light (world frame)
    Vec3 position{0, 0, 3};   ///< point light
};

/// What to draw: the shape at the origin (radius 1, z up; the cylinder 2 high, open), seen
/// from a perspective camera.
struct ShapeFrame {
    Shape shape = Shape::Sphere;
    Vec3 eye{0, -4, 2}, target{0, 0, 0}, up{0, 0, 1};
    double fovDegrees = 40;
    ShapeLight light;
};

class ShapeRenderer {
public:
    /// Reads the bank (its grids, not its PTM) and uploads the reference and the grid.
    static Result<std::unique_ptr<ShapeRenderer>> create(const std::string& bankPath);
    /// One frame into the renderer's own framebuffer (`width` x `height`, colour and depth).
    Status draw(const ShapeFrame& frame, int width, int height);
    GLuint framebuffer() const { return m_target.framebuffer.id(); }
    /// Where the bank's grid holds no measured LUT (light directions beyond what was measured,
    /// which a curved surface meets at its rim), how it is filled: an empty string when every
    /// node is measured or interpolated, else a line for the viewer's panel.
    const std::string& gridNote() const { return m_gridNote; }

private:
    ShapeRenderer() = default;
    LutBank m_bank;
    ShaderProgram m_program;
    GlVertexArray m_vertexArray;
    EngineMaterial m_material;  ///< the bank as btflut.glsl draws it (its images dropped once uploaded)
    GlTexture m_reference;
    EngineTextures m_textures;
    ColourDepthTarget m_target;
    int m_width = 0, m_height = 0;
    std::string m_gridNote;
    std::optional<PixelRect> m_window;  ///< what the shape wraps (sampleWindow), else the whole image
};

}  // namespace btflut
