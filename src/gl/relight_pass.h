#pragma once
// A bank's reference relit in texture space: the GL twin of `btflut relight`
// (Relighter::apply). One draw at the reference's resolution writes every texel once through
// the frame's LUTs, dithered per texel (so the dither moves with the texture, never with the
// screen), into a colour texture: a float one for `render --native`, or one of the
// reference's format whose mipmaps are then made from relit texels, so that a far quad shows
// the mean of LUT values rather than the LUT of a mean. Texel (x, row) of the image, row 0
// its top, is texel (x, row) of the target, as uploadMipmapped stores images. Banks that
// blend references blend in the same draw. Needs a current context.
//
//   RelightPass pass(bank, reference.id(), blend ? &*blend : nullptr);  // per bank
//   std::vector<GlTexture> luts = pass.makeLuts();                     // per target
//   pass.run(frame, luts, target.id(), /*dither=*/true);               // per light change
//
// Each target has its LUT textures of its own: updating LUTs that a pending draw still reads
// would make the driver wait for it.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/image/texel_region.h"
#include "core/relight/relighter.h"
#include "gl/objects.h"
#include "gl/prediction_textures.h"

namespace btflut {

/// lut_common.glsl's defines for a bank of LUTs: MAPS_REFERENCE, RGB_MODE, LUT_UNIFORMS.
std::vector<std::string> mapsReferenceDefines(const LutBank& bank);

class RelightPass {
public:
    /// `reference`: the bank's reference as a 2D texture read with texelFetch at level 0
    /// (unorm at the image's bit depth, or float); `blend`: the bank's textures when it blends
    /// references (LutBank::makesLuts), else null. Both must outlive the pass.
    RelightPass(const LutBank& bank, GLuint reference, const PredictionTextures* prediction);

    /// The LUT textures one target needs (1D per channel, or the blend's tables) and their bytes.
    std::vector<GlTexture> makeLuts() const;
    std::size_t lutBytes() const;

    /// Uploads the frame's LUTs into `luts` and draws the relit reference into level `level`
    /// of `target` (a colour-renderable 2D texture of the reference's size, with mipmaps past
    /// level 0). Past level 0 (banks with a predictor), each texel of the level is predicted
    /// from the planes' same level: the frame's LUTs must be that level's (LevelMatch::luts).
    /// Only the texels of `region` are written, if one is given (the rest keep what they held).
    /// Leaves its own framebuffer bound.
    Status run(const RelightFrame& frame, const std::vector<GlTexture>& luts, GLuint target, bool dither, int level = 0,
               const std::optional<TexelRegion>& region = {});

    /// The frame's LUTs into `luts` (made by makeLuts).
    void uploadLuts(const RelightFrame& frame, const std::vector<GlTexture>& luts) const;
    /// Binds `luts` from texture unit `first` (PredictionTextures::kUnits, or 3) and sets the
    /// uniforms lut_common.glsl's LUT functions read (and the blend's weights): what
    /// native.frag and scene.frag's LUT_FRAGMENT share.
    void bindLuts(const ShaderProgram& program, const RelightFrame& frame, const std::vector<GlTexture>& luts,
                  int first, int level = 0) const;
    /// lut_common.glsl's defines for this bank (the blend's, or mapsReferenceDefines), made once.
    const std::vector<std::string>& defines() const { return m_defines; }
    /// The predictor's own shader source, if any (PredictionTextures::sources): buildProgram's `generated`.
    const std::vector<ShaderFile>& sources() const;

private:
    Result<const ShaderProgram*> program(bool dither);

    const LutBank* m_bank;
    bool m_lutsAsUniforms;  ///< lutsAsUniforms(bank), asked of GL once
    GLuint m_reference;
    const PredictionTextures* m_prediction;
    std::vector<std::string> m_defines;
    std::map<bool, ShaderProgram> m_programs;  // by dither
    GlFramebuffer m_framebuffer;
    GlVertexArray m_vertexArray;
};

/// A relit texture for scenes: the reference's size and precision (R8 or R16 for grey, read
/// as (v, v, v); RGBA8 or RGBA16 for colour: RGB is not renderable everywhere), repeating and
/// trilinearly filtered; its mipmaps are made after each pass (GenerateMipmap).
GlTexture allocateRelitTexture(const Image& reference);
/// Its bytes on the GPU, mipmaps included.
std::size_t relitTextureBytes(const Image& reference);

}  // namespace btflut
