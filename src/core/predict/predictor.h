#pragma once
// The predictor of a bank that makes its LUTs at run time (LutBank::makesLuts): what places
// shadows and highlights per texel before each light's LUT matches the histogram
// (docs/predictors.md). One class per kind, each answering what relighting asks of it, so
// the relighter (relight/relighter.h) never branches on the kind. A kind's chunk of the
// .btflut file is its own too (kind_chunk.h, beside its class; the references' REFS is
// bank/predictor_chunks.cpp's), and what an engine reads of it (engineParts), and its part of
// an atlas's sidecar. Its GPU code is in shaders/ (kinds/, btflut.glsl's dispatcher,
// lut_common.glsl's #if branches).
//   reference_blend.h   K references blended with the light's barycentric weights
//   model_predictor.h   a linear light model (ptm, hsh, rbf, bln; a bank's PTM as one)
//   learned_predictor.h a learned model: per-texel codes and a small decoder network
//
//   const Predictor& p = bank.predictor();           // lut_bank.h: the bank holds one
//   PredictorFrame f = p.frameAt(light, view);       // per light change: integers
//   std::size_t q = p.code(f, texel, channel);       // 0 .. p.codes(), what the GPU computes
//
// The linear kinds' predictions are exact integer arithmetic (kWeightUnit, light_model.h), so
// the CPU and the GPU's shaders (shaders/lut_common.glsl, btflut.glsl) get the same codes; the
// learned kind's decoder is float, its GPU form generated per material (learned_shader.h).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/light_model.h"

namespace btflut {

/// What a GPU reads to predict: the one packing btflut's renderer uploads and `export` writes
/// (shaders/btflut.glsl, docs/engines.md).
struct PredictorPlanes {
    /// RGBA8: a light model's planes four to a layer (4-bit codes n stored as 17 n), or one
    /// reference to a layer (a grey one in R, G and B).
    std::vector<Image> layers;
    Image albedo;                    ///< RGB8, empty when none
    std::vector<float> scale, bias;  ///< a light model's, per plane, on the stored codes: (code - bias) scale
    /// A learned model's decoder: RGBA32F texels, a square `networkSize` a side
    /// (LearnedModel::gpuNetwork); empty for the other kinds.
    std::vector<float> network;
    int networkSize = 0;
};

/// The shader include's version (shaders/btflut.glsl's BTFLUT_GLSL_VERSION, checked equal by
/// tests/shader_forms_check.sh): what a learned material's sidecar asks for.
constexpr int kShaderIncludeVersion = 5;
/// A decoder specialised to a material (EngineParts::networkGlsl, networkHlsl) as `export`
/// writes it: GLSL (GLSL ES too), HLSL, Godot 4's (the GLSL text).
constexpr const char* kNetworkFiles[] = {"btflut_network.glsl", "btflut_network.hlsl", "btflut_network.gdshaderinc"};

/// What an engine reads of a predictor beside its planes (relight/engine_material.h,
/// docs/engines.md): each kind says its own.
struct EngineParts {
    LightBasis basis = LightBasis::Ptm;  ///< a light model's
    int order = 0;                       ///< hsh
    int planes = 0;                      ///< a light model's P, the references' K, the learned codes N
    int channels = 1;                    ///< the prediction's channels before any albedo: 1 or 3
    /// The albedo times the value (a light model's); false: the chroma after the match (lrgb references).
    bool albedoMultiplies = false;
    /// The weight grid's nodes a side and values per node (0: none, the weights in closed form:
    /// ptm, hsh; a learned model: 4, its decoder network), and the grid, [layer][j][i][4].
    int weightGridSize = 0, weights = 0;
    std::vector<float> weightGrid;
    /// A learned model's decoder specialised to it (learned_shader.h, after the include), GLSL
    /// (GLSL ES and Godot too) and HLSL, and its cost; no shader for a network past a shader's
    /// constants, which the include's texture path draws from the weight texture.
    std::string networkGlsl, networkHlsl;
    std::size_t texelMultiplyAdds = 0, frameMultiplyAdds = 0;
    int shaderVersion = 2;  ///< of the include it needs (material.json's shader_version)
};

/// The engine weight grid's nodes a side for rbf and references (bln: its own grid, read exactly).
constexpr int kEngineWeightGrid = 129;

/// `count` values per node of a size x size grid (node-major) as layers of four: [layer][node][4].
std::vector<float> weightsInLayers(const std::vector<float>& grid, std::size_t count, int size);

/// A uniform a predictor's shader code reads per light (shaders/lut_common.glsl): vectors of
/// `size` (1, 3 or 4) numbers, values.size() / size of them (an array, from its first element).
struct ShaderValues {
    std::string name;
    int size = 1;
    std::vector<float> values;
    bool integer = false;  ///< an int uniform (the values are whole numbers)
};

/// Writes an image beside an exported atlas and gives its file name (`export -o X.png`).
using TextureWriter = std::function<std::string(const std::string& suffix, const Image& image)>;
/// Images written with `texture` as "<prefix>-0", "<prefix>-1", ...: their file names, a JSON array.
nlohmann::json atlasImages(const std::vector<Image>& images, const std::string& prefix, const TextureWriter& texture);

struct LearnedFrame;

/// A predictor's integers at one light: the references blended and their weights (a
/// reference blend), the light model's per-light integers, or a learned model's prediction.
struct PredictorFrame {
    int count = 1;  ///< references blended, 1 to 3 (0 for a light model)
    std::array<int, 3> references{0, 0, 0};
    std::array<std::int32_t, 3> weights{kWeightUnit, 0, 0};  ///< in 1 / kWeightUnit, summing to kWeightUnit
    LightModelFixed model;                                   ///< a light model's per-light integers
    /// A learned model's light and its prediction there, decoded when first read
    /// (learned_predictor.h).
    std::shared_ptr<LearnedFrame> learned;
};

/// A bank's kind: the one enum C++, the shaders (BtflutPredictor.kind, BTFLUT_KIND_* in
/// gpu_constants.h) and material.json ("kind", predictorKindName) share. Luts: the paper's
/// bank of LUTs, which has no predictor (and no BtflutPredictor). The .btflut file keeps its
/// own numbers (bank_format.h, FilePredictor).
enum class PredictorKind : int {
    Luts = 0,
    Model = BTFLUT_KIND_MODEL,
    References = BTFLUT_KIND_REFERENCES,
    Learned = BTFLUT_KIND_LEARNED,
};
/// Each kind's name (material.json's "kind"): a new kind's line here, beside its enum's.
constexpr std::array kPredictorKindNames{
    std::pair{PredictorKind::Luts, "luts"},
    std::pair{PredictorKind::Model, "model"},
    std::pair{PredictorKind::References, "references"},
    std::pair{PredictorKind::Learned, "learned"},
};
/// "luts", "model", "references" or "learned".
constexpr const char* predictorKindName(PredictorKind kind) {
    for (const auto& [k, name] : kPredictorKindNames)
        if (k == kind) return name;
    return "luts";
}

class Predictor {
public:
    virtual ~Predictor() = default;

    virtual PredictorKind kind() const = 0;

    /// The name `--predictor` takes: "references", the light model's (ptm, hsh2, bln9c) or the
    /// learned model's (neural9).
    virtual std::string name() const = 0;
    /// Bytes per texel it stores (the region labels, a bank's, not counted).
    virtual double bytesPerTexel() const = 0;
    /// Multiply-adds per texel of its prediction at a light (what a moving light costs a GPU per
    /// texel beyond the LUT; auto bounds it: AutoBakeOptions::decodeBudget).
    virtual std::size_t multiplyAdds() const = 0;
    /// What it is, in words, for `info` and the viewer: "hsh2 (4 bytes per texel), relit per
    /// light", "3 reference(s) blended per light".
    virtual std::string description() const = 0;
    /// Codes of a predicted value: 255 (a channel) or 765 (the grey of RGB8, three channels'
    /// codes summed).
    int codes() const { return m_codes; }
    /// Channels predicted and matched apart: 3 (rgb banks) or 1 (the grey).
    int channels() const { return m_channels; }

    /// Why a GPU cannot draw it (past the shaders' arrays), in one line naming no file; empty
    /// when it can, as every kind but a learned model too large can.
    virtual std::string beyondGpu() const { return {}; }
    /// What decoding it adds to a texel relit in texture space (`perFragment` false) or to a
    /// pixel drawn per fragment, in pixels shaded flat on llvmpipe (the renderer's choice of
    /// path, gl/scene_quads.cpp): 0 where the path's own cost holds it (the linear kinds' few
    /// multiply-adds).
    virtual double decodeCost(bool /*perFragment*/) const { return 0.0; }
    /// Its planes as a GPU holds them.
    virtual PredictorPlanes planes() const = 0;
    /// What an engine reads of it beside its planes; `file` names the material's files (a
    /// learned decoder's shader names it).
    virtual EngineParts engineParts(const std::string& file) const = 0;
    /// Its fields of material.json's "predictor" (docs/engines.md) beside every kind's (kind,
    /// images, planes, scale and bias, the weight file's format): how its images hold it, and
    /// what its own parts (`parts`, its engineParts) are: a basis, a network's shader files, its
    /// weights' rows (in "weights", where it has a weight grid).
    virtual void materialFields(nlohmann::json& predictor, const EngineParts& parts) const = 0;
    /// Its part of an exported atlas's sidecar (docs/predictors.md): what it holds, in `blend`,
    /// its images written beside the atlas with `texture`.
    virtual void atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const = 0;
    /// The #defines that choose and size its prediction in shaders/lut_common.glsl (PREDICT_...).
    virtual std::vector<std::string> shaderDefines() const = 0;
    /// GLSL its shader code needs after the include, made for this predictor (a learned model's
    /// decoder specialised to it: learned_shader.h); empty for most kinds.
    virtual std::string shaderSource() const { return {}; }
    /// What that code reads at a light: its frame's integers as uniforms.
    virtual std::vector<ShaderValues> shaderValues(const PredictorFrame& frame) const = 0;

    /// Its integers at a light, seen from `view` (read only by a predictor of views).
    virtual PredictorFrame frameAt(Direction light, Direction view) const = 0;
    /// Whether its predictions change with the view: a learned model of rectified views,
    /// whose bank has a layer per view (the others predict one camera's images).
    virtual bool viewDependent() const { return false; }
    /// A texel's predicted code, 0 .. codes(), of `channel` (< channels()).
    virtual std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const = 0;
    /// A texel's colour before a grey LUT (RGB in [0, 1]): its chroma is what a grey bank of
    /// RGB keeps.
    virtual void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const = 0;
    /// The codes a GPU predicts from level `level` of its planes' mipmaps, at `texels` of that
    /// level (x + y * its width): level m's texel (x, y) is the mean of the reference's
    /// (`width` x `height`) 2^m square at (2^m x, 2^m y), rounded to bytes (levelBlock), as
    /// GenerateMipmap makes levels. What relighting a level directly reads (relight/
    /// level_match.h). The default rounds the mean of the square's codes: a linear
    /// predictor's. The learned kind decodes its codes' means (a network of means is not the
    /// mean of its values). Level 0: code(), decoding only `texels`. `codes`: channels() per
    /// texel.
    virtual void levelCodes(const PredictorFrame& frame, int level, int width, int height,
                            std::span<const std::uint32_t> texels, std::vector<std::size_t>& codes) const;

    /// The codes of `texels` counted, code q at counts[q + 1] (codes() + 2 counts): what
    /// matching reads per light, one call for a region rather than one per texel.
    virtual void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                            std::vector<std::uint64_t>& counts) const = 0;

protected:
    Predictor(int matchedChannels, int codeCount) : m_channels(matchedChannels), m_codes(codeCount) {}

private:
    int m_channels;
    int m_codes;
};

/// The reference's texels under level `level`'s texel `texel` (x + y * that level's width,
/// a level being half the one above, rounded down, at least 1): its 2^level square, clipped.
std::vector<std::uint32_t> levelBlock(int level, int width, int height, std::uint32_t texel);
/// A level's size along an axis of `size` texels, as GL's mipmaps halve it.
inline int levelSize(int size, int level) { return std::max(1, size >> level); }
/// The mip levels of a `width` x `height` texture, down to 1 x 1.
inline int levelCount(int width, int height) {
    int levels = 1;
    for (int side = std::max(width, height); side > 1; side /= 2) ++levels;
    return levels;
}
/// One texel of level `level` of an image of bytes (`channels` per texel, rows of `width`):
/// its square's mean per channel (levelBlock), rounded half up, into `out`. The one definition
/// of a level's byte, for the GPU's planes (levelOfBytes) and the CPU's emulation of them.
void levelTexelBytes(std::span<const std::uint8_t> bytes, int width, int height, int channels, int level,
                     std::uint32_t texel, std::uint8_t* out);
/// Level `level` of an image of bytes (`channels` per texel, rows of `width`) as a GPU holds
/// a predictor's planes' mipmaps (PredictionTextures, made here rather than by the driver, whose
/// rounding varies): each texel its square's mean (levelBlock), rounded half up.
std::vector<std::uint8_t> levelOfBytes(std::span<const std::uint8_t> bytes, int width, int height, int channels,
                                       int level);
/// The mean of `count` bytes summing to `sum`, rounded half up: a level's byte.
inline std::uint8_t meanByte(std::uint32_t sum, std::size_t count) {
    return static_cast<std::uint8_t>((2 * sum + count) / (2 * count));
}

/// countCodes for a kind whose code() is final: the loop, its calls inlined.
template <class Kind>
void countCodesOf(const Kind& kind, const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                  std::vector<std::uint64_t>& counts) {
    for (std::uint32_t texel : texels) ++counts[kind.Kind::code(frame, texel, channel) + 1];
}

/// A fixed-point sum (in 1 / kWeightUnit) rounded to a code, 0 .. codes: floor(sum /
/// kWeightUnit + 1/2), exact in float too, the sum being an integer below 2^24.
inline std::size_t roundedCode(std::int64_t sum, int codes) {
    const std::int64_t code = (sum + kWeightUnit / 2) / kWeightUnit;
    return static_cast<std::size_t>(code < 0 ? 0 : code > codes ? codes : code);
}

}  // namespace btflut
