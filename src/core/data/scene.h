#pragma once
// Scenes for `btflut render SCENE.json` (format: docs/scene.md): a perspective camera, one
// directional light, and textured quads, each with a material (a .btflut bank) and a mode.
//
//   Result<Scene> scene = loadScene("demo.json");
//   std::vector<std::size_t> visible = visibleQuads(*scene);   // frustum culling
//
// World frame: right-handed, z up. A quad's tangent frame is (tangent, bitangent = normal x
// tangent, normal); its texture's x runs along the tangent and y along the bitangent, so the
// material's sample frame is the quad's tangent frame.

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/result.h"

namespace btflut {

/// lut: the LUT for the quad's light and view; brdf: the paper's 2D texture mapping (the
/// texture scaled by the target-to-reference mean grey); ptm: the bank's polynomial texture
/// map; flat: the plain texture; nearest: the measured image nearest to the light direction.
enum class RenderMode { Lut, Brdf, Ptm, Flat, Nearest };

struct SceneMaterial {
    std::string bank;    ///< .btflut path (relative paths resolved against the scene's folder)
    std::string images;  ///< the dataset it was baked from, for mode nearest; may be empty
};

struct SceneQuad {
    std::string material;
    Vec3 center, normal, tangent;  ///< normal and tangent unit and orthogonal after loading
    double width = 1, height = 1;  ///< along the tangent and the bitangent
    double uvScale = 1;            ///< texture repeats across the quad
    RenderMode mode = RenderMode::Lut;
};

/// The scene format's version ("btflut_scene"); scenes of another are refused.
constexpr int kSceneVersion = 1;

struct Scene {
    std::string file;
    int width = 1024, height = 1024;
    Vec3 eye{0, -3, 2}, target{0, 0, 0}, up{0, 0, 1};
    double fovDegrees = 45;
    /// > 0: an orthographic camera whose image spans this height (world units) and `fovDegrees`
    /// is unused; the view direction is then the same everywhere (the viewer's 2D mode).
    double orthographicHeight = 0;
    Vec3 light{0, 0, 1};  ///< unit vector towards the light, world frame
    std::map<std::string, SceneMaterial> materials;
    bool interpolateLuts = true;  ///< false: the LUT of the nearest measured direction (for comparison)
    /// Banks with a predictor: the LUT made at the light by counting the prediction (CPU work
    /// per light change, drawn in texture space only) rather than read from the bank's baked
    /// grid ("interpolation": "exact").
    bool exactMatch = false;
    bool dither = true;  ///< mode lut dithers per texel (lut.h), so the histogram is the target's
    std::vector<SceneQuad> quads;
};

/// "lut", "brdf", "ptm", "flat" or "nearest".
Result<RenderMode> parseRenderMode(const std::string& name);

/// Parses and validates a scene; errors name the file and the field (not JSON, unknown
/// material, degenerate quad, NaN or zero direction, zero-sized image, ...).
Result<Scene> parseScene(const std::string& text, const std::string& file, const std::string& folder);
Result<Scene> loadScene(const std::string& path);

/// The scene as a scene file, which parseScene reads back: material paths absolute, or, with
/// `folder` (where the file will be), relative to it for those inside it, so the folder can
/// move with them (those outside stay absolute).
std::string sceneToJson(const Scene& scene, const std::string& folder = {});

/// 4x4 column-major view-projection matrix of the scene's camera (OpenGL clip space).
std::array<float, 16> viewProjection(const Scene& scene);

/// Indices of the quads not entirely outside the view frustum.
std::vector<std::size_t> visibleQuads(const Scene& scene);

/// The texture coordinates (uv scale applied, not wrapped; x along the tangent, y down the
/// image like its rows) of the point of `quad`'s plane seen through the pixel centre
/// (x + 1/2, row + 1/2) of the scene's image (row 0 at the top); nothing when the ray is
/// parallel to the plane.
std::optional<std::array<double, 2>> quadTextureAt(const Scene& scene, const SceneQuad& quad, int x, int row);

/// The same for many pixels of one camera: the inverse of its projection computed once.
class PixelRays {
public:
    explicit PixelRays(const Scene& scene);
    std::optional<std::array<double, 2>> quadTextureAt(const SceneQuad& quad, int x, int row) const;
    /// Where the pixel's ray meets the quad's plane: its texture coordinates (as above) and
    /// its distance from the near plane along the ray (negative: behind it).
    struct QuadHit {
        std::array<double, 2> uv;
        double distance;
    };
    std::optional<QuadHit> hit(const SceneQuad& quad, int x, int row) const;

private:
    std::array<double, 16> m_inverse;
    int m_width, m_height;
};

/// normal x tangent: the quad's texture y runs along it (up the image).
Vec3 bitangentOf(const SceneQuad& quad);

/// A world vector in a quad's tangent frame (the material's sample frame): z > 0 is in
/// front of the quad.
Vec3 toQuadFrame(const SceneQuad& quad, const Vec3& world);

const char* renderModeName(RenderMode mode);

}  // namespace btflut
