#pragma once
// The GPU side of a bank that blends references and matches regions (LutBank::Prediction,
// core/relight/relighter.h): its textures, the shader defines of lut_common.glsl's PREDICT path, and
// the per-light uniforms and LUT tables. Shared by the native and the scene renderer.
//
//   PredictionTextures t = PredictionTextures::upload(bank, bytes);     // per bank
//   std::vector<GlTexture> luts = t.makeLutTables();          // per quad
//   t.updateLuts(luts, frame);                                // per light change
//   t.bind(program, frame, luts, 1);                          // per draw: units 1.. and uniforms

#include <memory>
#include <string>
#include <vector>

#include "core/relight/relighter.h"
#include "gl/objects.h"
#include "gl/shader.h"

namespace btflut {

/// True when a bank applies its frame's LUTs (RelightFrame::luts) from uniforms
/// (lut_common.glsl's LUT_UNIFORMS: at most 3 x 256 floats, and room for them in the current
/// context), else from textures. Only on a software rasteriser: read as an array, uniforms cost
/// llvmpipe a third of a filtered fetch per pixel, but a GPU serves uniforms from a constant
/// cache that serialises a warp's distinct indices (a LUT read per texel is as divergent as the
/// texture), where its texture cache serves a table at full rate (issue 46).
bool lutsAsUniforms(const LutBank& bank);

class PredictionTextures {
public:
    static constexpr int kUnits = 6;  ///< texture units bind uses from its first: planes, labels, 3 LUTs, network

    /// Uploads the predictor's planes (Predictor::planes: RGBA8 layers, then the albedo's; a
    /// learned model's decoder) and the labels; adds their bytes to `bytes`.
    static PredictionTextures upload(const LutBank& bank, std::size_t& bytes);

    /// BLEND, the predictor's own (Predictor::shaderDefines), REGIONS, RGB_MODE, PREDICT_MATCH, LUT_UNIFORMS:
    /// made once by upload.
    const std::vector<std::string>& defines() const { return m_defines; }
    /// The predictor's own shader source (Predictor::shaderSource), made once: buildProgram's
    /// `generated`.
    const std::vector<ShaderFile>& sources() const { return m_sources; }

    /// LUT tables for one user of the bank (one per channel, a row per region), and their bytes.
    std::vector<GlTexture> makeLutTables() const;
    std::size_t lutTableBytes() const;
    /// Uploads a frame's LUTs into tables made by makeLutTables.
    void updateLuts(const std::vector<GlTexture>& tables, const RelightFrame& frame) const;
    /// Binds the textures and `tables` to units first .. first + kUnits - 1 and sets the
    /// frame's uniforms. `level` > 0: the prediction reads that level of the planes' mipmaps
    /// (a relight pass of one level, level_match.h), made the first time it is asked for (each
    /// level the 2 x 2 mean of the one above); every other draw reads level 0.
    void bind(const ShaderProgram& program, const RelightFrame& frame, const std::vector<GlTexture>& tables, int first,
              int level = 0) const;

private:
    const LutBank* m_bank = nullptr;
    const Predictor* m_predictor = nullptr;  ///< the bank's
    bool m_lutsAsUniforms = false;           ///< lutsAsUniforms(bank), asked of GL once
    std::vector<std::string> m_defines;
    std::shared_ptr<const std::string> m_source;  // m_sources' text, at one address when moved
    std::vector<ShaderFile> m_sources;
    GlTexture m_planes, m_labels, m_network;
    mutable bool m_planeMipmaps = false;    ///< made (bind at a level)
    mutable bool m_mipmapFiltered = false;  ///< the planes' filter reads them (texelFetch past level 0 needs it)
};

}  // namespace btflut
