#pragma once
// Draws a Scene (core/scene.h) with OpenGL, doing only the work the view needs: quads outside
// the frustum are culled, and only materials that a visible quad uses are loaded and uploaded
// (once). Per frame, each lit quad's LUT is blended for the light (constant over a flat quad
// under a directional light) and uploaded only when the light changed. Needs the context
// that was current at creation.
//
//   Result<std::unique_ptr<SceneRenderer>> r = SceneRenderer::create(scene);
//   (*r)->draw(scene.light);  Image img = (*r)->readBack();
//
// Modes: lut (the LUT), flat (the plain texture), brdf (the paper's "2D texture mapping": the
// texture scaled by the ratio of the target's mean grey to the reference's).

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/lut_bank.h"
#include "core/scene.h"
#include "gl/objects.h"

namespace btflut {

struct RenderStats {
    std::vector<std::string> loadedMaterials;   ///< names, in load order
    std::vector<std::string> skippedMaterials;  ///< used by no visible quad: never read
    std::size_t quadsDrawn = 0, quadsCulled = 0, quadsUnlit = 0;
    std::size_t textureBytes = 0;  ///< reference textures with mipmaps, plus LUT textures
};

class SceneRenderer {
public:
    static Result<std::unique_ptr<SceneRenderer>> create(const Scene& scene);

    /// One frame for a light (unit vector, world frame); `mode` overrides every quad's.
    Status draw(const Vec3& light, std::optional<RenderMode> mode = {});
    /// Waits for the GPU (for timing).
    void finish() const;
    Image readBack() const;
    const RenderStats& stats() const { return m_stats; }

private:
    struct Material {
        LutBank bank;
        GlTexture reference;
        LevelCounts referenceGrey;  ///< for the brdf mode's mean
    };
    struct QuadState {
        std::size_t index;
        std::vector<GlTexture> luts;  ///< one per channel
        Vec3 lightUploaded{0, 0, -2};  ///< the light its LUTs were blended for
        float brightness = 1;
        bool unlit = false;
    };
    SceneRenderer() = default;
    Result<GLuint> program(RenderMode mode, const LutBank& bank);
    void updateLut(QuadState& q, const Vec3& light);

    Scene m_scene;
    std::map<std::string, Material> m_materials;
    std::vector<QuadState> m_quads;
    std::map<std::vector<std::string>, GlProgram> m_programs;  ///< by defines
    GlTexture m_target, m_depth;
    GlFramebuffer m_framebuffer;
    GlVertexArray m_vertexArray;
    RenderStats m_stats;
};

/// Creates a renderer, draws one frame for the scene's light and reads it back.
Result<Image> renderScene(const Scene& scene, RenderStats& stats);

}  // namespace btflut
