#pragma once
// Draws a Scene (core/data/scene.h) with OpenGL, doing only the work the view needs: quads outside
// the frustum are culled; only materials that a visible quad uses are loaded and uploaded
// (once); a material's PTM is read only when a quad is first drawn in mode ptm, and a
// measured image only when mode nearest first needs it. Needs the context that was current
// at creation.
//
//   Result<std::unique_ptr<SceneRenderer>> r = SceneRenderer::create(scene);
//   (*r)->draw(scene.light);  Image img = (*r)->readBack();
//
// Mode lut, banks of one view layer: under a directional light a flat quad's LUT is constant,
// so the reference is relit in texture space (RelightPass: one pass at the reference's size,
// dithered per texel, mipmaps made from the relit texels) and the quad is drawn with the flat
// shader. Quads of one material under the same light direction (in their own frames) share
// the relit texture; it is redone only when the light changed, so a frame whose light did not
// move costs what a flat frame costs. Only the texels the quads show are relit (seenRegion),
// at the finest mip level they read (relitLevel).
//
// While the light moves, a new direction each frame, the pass would relight the whole
// reference every frame: a quad then draws per fragment instead (LUT_FRAGMENT in scene.frag:
// the prediction, or the filtered reference, through the frame's LUTs, the pass's shader code),
// when that costs less than the pass (the pixels it covers against the texels to relight:
// choosePaths). When the light stops, the next frame relights in texture space and the frames
// after it draw flat. Both paths take the same LUTs: banks with a predictor read their match
// LUTs from the baked grid (Relighter::gridFrame; "interpolation": "exact" makes them at the
// light by counting the prediction), so a light change costs no per-texel work on the CPU.
//
// Mode lut, banks with several view layers: the view direction changes across a quad under a
// perspective camera, so the LUT is blended on the CPU for a kViewGrid x kViewGrid grid of
// points on the quad and the shader interpolates between them (a 3D texture). So that a far
// quad is not the LUT of averaged texels, each mipmap level has its own LUT (MipLuts); the
// shader picks the two levels around its footprint, as trilinear filtering would.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/bank/mip_luts.h"
#include "core/data/dataset.h"
#include "core/data/scene.h"
#include "core/image/image.h"
#include "core/image/texel_region.h"
#include "core/relight/level_match.h"
#include "core/relight/relighter.h"
#include "gl/objects.h"
#include "gl/prediction_textures.h"
#include "gl/relight_pass.h"
#include "gl/textures.h"

namespace btflut {

/// GPU memory of the textures, by use (bytes as the driver stores them: RGB padded to RGBA,
/// mipmap chains included).
struct TextureBytes {
    std::size_t reference = 0;   ///< the reference image (modes lut of classic banks, brdf, flat)
    std::size_t prediction = 0;  ///< the predictor's planes, albedo and labels (mode lut of banks with a predictor)
    std::size_t relit = 0;       ///< mode lut's relit textures (one per material and light direction) and their LUTs
    std::size_t luts = 0, ptm = 0, images = 0;
    std::size_t total() const { return reference + prediction + relit + luts + ptm + images; }
};

/// How mode lut draws a bank of one view layer.
enum class LutPath {
    Auto,          ///< per quad and frame, whichever costs less (choosePaths)
    TextureSpace,  ///< relit textures only
    PerFragment,   ///< per fragment only
};

struct SceneRendererOptions {
    /// The camera stays where the scene puts it: a bank's view layers that no visible quad's
    /// view directions use are not decoded. A viewer that moves the camera says false.
    bool fixedCamera = true;
    LutPath lutPath = LutPath::Auto;
    /// Per fragment, the prediction without its LUT (bench render's baseline: an RTI viewer).
    bool predictionOnly = false;
};

struct RenderStats {
    std::vector<std::string> loadedMaterials;          ///< names, in load order
    std::vector<std::string> skippedMaterials;         ///< used by no visible quad: never read
    std::vector<std::string> loadedPtms;               ///< materials whose PTM a ptm quad needed
    std::size_t imagesLoaded = 0;                      ///< measured images read for mode nearest
    std::size_t viewLayers = 0, viewLayersLoaded = 0;  ///< over the loaded banks
    std::size_t quadsDrawn = 0, quadsCulled = 0, quadsUnlit = 0;
    std::size_t relitTextures = 0;  ///< mode lut's relit textures held (per material and light direction)
    std::size_t relightPasses = 0;  ///< passes run, since creation
    /// Texels those passes relit: a quad minified 2^m times is relit at mip level m alone
    /// (LevelMatch), 1/4^m of its reference's texels.
    std::size_t relitTexels = 0;
    /// The last frame's lit mode lut quads of banks of one view layer: drawn from a relit
    /// texture, or relit per fragment.
    std::size_t quadsTextureSpace = 0, quadsPerFragment = 0;
    TextureBytes textureBytes;
};

/// Every `stride`-th pixel of a frame across and down (stride odd, so each sample is one
/// pixel's own value), for plots of large frames.
struct FrameSamples {
    int width = 0, height = 0, stride = 1;  ///< samples across and down
    int frameHeight = 0;
    std::vector<std::uint8_t> rgb;      ///< 3 bytes per sample, top row first
    std::vector<std::uint8_t> covered;  ///< 1 where a quad was drawn
    /// The frame pixel (row 0 at the top) of sample (i, j).
    int pixelX(int i) const { return i * stride + stride / 2; }
    int pixelRow(int j) const { return frameHeight - 1 - ((height - 1 - j) * stride + stride / 2); }
};

class SceneRenderer {
public:
    static constexpr int kViewGrid = 5;

    static Result<std::unique_ptr<SceneRenderer>> create(const Scene& scene, const SceneRendererOptions& options = {});

    /// One frame for a light (unit vector, world frame); `mode` overrides every quad's.
    Status draw(const Vec3& light, std::optional<RenderMode> mode = {});
    /// A new image size (keeps everything loaded).
    Status resize(int width, int height);
    /// Moves the camera (the set of visible quads is fixed at creation); only for a renderer
    /// created with SceneRendererOptions::fixedCamera false. `orthographicHeight` > 0: an
    /// orthographic camera (Scene::orthographicHeight).
    void setCamera(const Vec3& eye, const Vec3& target, const Vec3& up, double orthographicHeight = 0);
    /// Nearest-node LUTs instead of interpolated ones.
    void setInterpolation(bool interpolate);
    /// Waits for the GPU (for timing).
    void finish() const;
    Image readBack() const;
    /// The last frame's samples (a nearest blit into a small target, then one small read).
    FrameSamples sampleFrame(int stride);
    GLuint framebuffer() const { return m_framebuffer.id(); }
    const Scene& scene() const { return m_scene; }
    const RenderStats& stats() const { return m_stats; }
    /// A visible quad's material bank, or null (for viewers that show LUTs and histograms).
    const LutBank* bank(const std::string& material) const;
    /// The LUT a quad's centre gets for a light (what mode lut applies there): its blend and,
    /// per region and channel, its LUT.
    RelightFrame centreFrame(std::size_t quad, const Vec3& light) const;

private:
    /// A material's reference relit for one light direction (in the quads' own frame).
    struct Relit {
        Vec3 light, view;  ///< in the quad's frame (view: what a predictor of views is relit for)
        GlTexture texture;
        int level = 0;                ///< its mipmap level relit (and those below it, mipmapped from it)
        TexelRegion region;           ///< ... and the texels of it that hold the relight (level-0 texels)
        std::vector<GlTexture> luts;  ///< the pass's, of this texture alone
        std::uint64_t lastUsed = 0;   ///< the frame that last drew it
    };
    struct Material {
        LutBank bank;
        GlTexture reference;                 ///< uploaded when a mode first needs it
        std::optional<Relighter> relighter;  ///< the LUTs (and blend) per light
        std::optional<PredictionTextures>
            prediction;                        ///< banks with a predictor: uploaded when mode lut first needs them
        std::optional<RelightPass> pass;       ///< banks of one view layer, mode lut
        std::vector<Relit> relit;              ///< by light direction
        std::optional<MipLuts> mipLuts;        ///< banks with view layers, mode lut
        std::optional<LevelMatch> levelMatch;  ///< banks with a predictor relit at a mip level (LevelMatch::supports)
        LevelCounts referenceGrey;             ///< for the brdf mode's mean
        bool ptmLoaded = false;
        std::array<GlTexture, 3> ptm;  ///< coefficients 0-2, 3-5, albedo
        std::array<float, 6> ptmScale{}, ptmBias{};
        std::optional<Dataset> images;
        std::map<std::string, GlTexture> imageTextures;  ///< by dataset image name
    };
    /// A light below the horizon, which no quad is ever lit by: "none yet", or "compute again"
    /// where a quad's state records the light it was computed for.
    static constexpr Vec3 kNoLight{0, 0, -2};

    struct QuadState {
        std::size_t index;
        /// banks with view layers: per channel, 3D over the view grid and mip levels; of one view
        /// layer drawn per fragment: the frame's LUTs (RelightPass::makeLuts)
        std::vector<GlTexture> luts;
        Vec3 light;  ///< in the quad's frame
        /// The view it is relit for (relitLut): a predictor of views, its centre's in its frame;
        /// else the bank's one layer's.
        Vec3 view{0, 0, 1};
        std::size_t relit = 0;                       ///< mode lut relit (relitLut): its material's relit texture
        int level = 0;                               ///< ... whose finest mip level it reads (finestLevel)
        TexelRegion region;                          ///< ... and the texels it shows (seenRegion)
        bool perFragment = false;                    ///< ... or relit per fragment this frame (choosePaths)
        Vec3 lastFrameLight = kNoLight;              ///< the light in its frame at the previous frame
        RelightFrame frame;                          ///< per fragment: the frame in `luts`
        Vec3 frameLight = kNoLight, frameView;       ///< ... and the light and view (in the quad's frame) it is for
        Vec3 lightUploaded = kNoLight, eyeUploaded;  ///< what its state was computed for
        RenderMode modeUploaded = RenderMode::Flat;
        float brightness = 1;  ///< brdf mode
        bool unlit = false;
        std::array<float, 7> ptmWeights{};  ///< per coefficient weights and the offset
        std::string nearestImage;
    };
    SceneRenderer() = default;
    Result<const ShaderProgram*> program(RenderMode mode, const Material& material, bool unlit, bool perFragment);
    Vec3 viewAt(const SceneQuad& quad, double x, double y) const;
    std::vector<Direction> viewGridDirections(const SceneQuad& quad) const;
    std::vector<Direction> viewsOf(const std::string& material, const std::vector<std::size_t>& visible) const;
    void update(QuadState& q, const Vec3& light, RenderMode mode);
    Status prepare(QuadState& q, RenderMode mode, const Vec3& light);
    /// Mode lut on banks of one view layer: the relit textures this frame's lights need.
    Status relight(const std::vector<RenderMode>& modes);
    /// Mode lut drawn relit (in texture space or per fragment): a bank of one view layer, or
    /// a predictor of views, relit for the quad's centre view (the others blend view layers).
    bool relitLut(const QuadState& q, RenderMode mode) const;
    bool relitInTextureSpace(const QuadState& q, RenderMode mode) const;
    /// Mode lut on banks of one view layer: per fragment or in texture space, per quad.
    void choosePaths(const std::vector<RenderMode>& modes);
    /// A point of a quad in clip space (x, y, z, w) and its quad coordinates (s, t) in [-1, 1]^2.
    using ClipPoint = std::array<double, 6>;
    /// The quad clipped to the view volume (w > 0 and the four sides): empty when unseen.
    std::vector<ClipPoint> clippedQuad(const SceneQuad& quad) const;
    /// The pixels a quad covers on screen (its projection, clipped to the image; occlusion ignored).
    double coveredPixels(const SceneQuad& quad) const;
    /// The texels of its texture (`texelsWide` x `texelsHigh`) that filtering reads on the
    /// part of a quad on screen, at every mip level it reads there (level-0 texels).
    TexelRegion seenRegion(const SceneQuad& quad, int texelsWide, int texelsHigh) const;
    /// The mip level a quad's relit texture is relit from: finestLevel, for banks relit by
    /// level (LevelMatch::supports, LUTs read from the bank's grid); else 0.
    int relitLevel(const Material& material, const SceneQuad& quad) const;
    /// The finest mip level of its texture (`texelsWide` x `texelsHigh`) that trilinear
    /// filtering reads anywhere on a quad: floor of GL's level of detail at its nearest point
    /// (0 where it reaches behind the eye).
    int finestLevel(const SceneQuad& quad, int texelsWide, int texelsHigh) const;
    /// GL's level of detail (log2 of texels per pixel) at a quad's point (s, t): none where it
    /// is behind the eye or seen edge on.
    std::optional<double> levelOfDetail(const SceneQuad& quad, double s, double t, int texelsWide,
                                        int texelsHigh) const;
    /// A frame of a material's LUTs for a light and view, as the scene asks (grid, exact, nearest).
    RelightFrame frameFor(const Material& material, Direction light, Direction view) const;
    void bindPerFragment(const ShaderProgram& program, const QuadState& q, const Material& material) const;

    Scene m_scene;
    bool m_interpolate = true;
    bool m_exactMatch = false;
    LutPath m_lutPath = LutPath::Auto;
    bool m_predictionOnly = false;
    bool m_fixedCamera = true;
    bool m_dither = true;
    std::uint64_t m_frame = 0;
    std::map<std::string, Material> m_materials;
    std::vector<QuadState> m_quads;
    std::map<std::vector<std::string>, ShaderProgram> m_programs;  ///< by defines (and generated source)
    GlTexture m_target, m_depth;
    ColourDepthTarget m_samples;  ///< sampleFrame's, at its last size
    int m_samplesWidth = 0, m_samplesHeight = 0;
    GlFramebuffer m_framebuffer;
    GlVertexArray m_vertexArray;
    RenderStats m_stats;
};

/// Creates a renderer, draws one frame for the scene's light and reads it back.
Result<Image> renderScene(const Scene& scene, RenderStats& stats);

}  // namespace btflut
