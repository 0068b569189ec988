#pragma once
// A learned model (learned_model.h) as a bank's predictor: per texel its codes, decoded by the
// bank's network at each light (LearnedModel::decoderCost multiply-adds a texel). Counting a
// sample's codes decodes the sample's texels; the first texel's code read decodes every texel
// of the frame, once, so the next are lookups. Also what an engine reads of it, and its chunk
// of the .btflut file (LRND).

#include <mutex>

#include "core/io/byte_stream.h"
#include "core/predict/chunk_planes.h"
#include "core/predict/kind_chunk.h"
#include "core/predict/learned_model.h"
#include "core/predict/predictor.h"
#include "core/predict/predictor_fit.h"

namespace btflut {

/// A frame's light (and view) and, once read, every texel's channel codes (0..255) there, and once asked
/// for, the uniforms a GPU reads there (a renderer asks at every draw; the light changes less).
struct LearnedFrame {
    Direction light, view;
    std::once_flag once;
    std::vector<std::uint8_t> codes;
    std::once_flag uniformsOnce;
    std::vector<ShaderValues> uniforms;
};

class LearnedPredictor final : public Predictor {
public:
    /// `perChannel`: its RGB matched per channel (rgb banks); else its grey, on the scale of
    /// the summed channel codes when it has colour.
    LearnedPredictor(LearnedModel model, bool perChannel);

    PredictorKind kind() const override { return PredictorKind::Learned; }
    std::string name() const override { return learnedModelName(m_model); }
    double bytesPerTexel() const override { return m_model.codes; }
    /// The decoder's per texel as it is drawn (learned_shader.h): a residual that validation left
    /// constant is not evaluated, and the light's part is once per light.
    std::size_t multiplyAdds() const override;
    std::string description() const override;
    /// A model whose networks exceed the shader's arrays (LearnedModel::fitsGpu; `bake` trains
    /// none) is relit on the CPU only.
    std::string beyondGpu() const override;
    /// Its decoder's, in proportion to its multiply-adds (measured for neural9).
    double decodeCost(bool perFragment) const override;
    PredictorPlanes planes() const override;
    /// Its decoder network as the weight grid (btflut.glsl), and its shader specialised to it.
    EngineParts engineParts(const std::string& file) const override;
    void atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const override;
    void materialFields(nlohmann::json& predictor, const EngineParts& parts) const override;
    std::vector<std::string> shaderDefines() const override;
    /// The decoder specialised to the model (learned_shader.h); empty for a network past a
    /// shader's constants, which the include's texture path draws.
    std::string shaderSource() const override;
    std::vector<ShaderValues> shaderValues(const PredictorFrame& frame) const override;
    PredictorFrame frameAt(Direction light, Direction view) const override;
    bool viewDependent() const override { return m_model.viewFeatures > 0; }
    std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const override;
    void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const override;
    void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                    std::vector<std::uint64_t>& counts) const override;
    /// Decodes the means of its codes (their bytes rounded, as an RGBA8 mipmap holds them).
    void levelCodes(const PredictorFrame& frame, int level, int width, int height,
                    std::span<const std::uint32_t> texels, std::vector<std::size_t>& codes) const override;

    const LearnedModel& model() const { return m_model; }

private:
    const std::uint8_t* decoded(const PredictorFrame& frame, std::size_t texel) const;
    std::size_t codeOf(const std::uint8_t* channels, int channel) const;

    LearnedModel m_model;
    bool m_perChannel;
};

/// Its chunk of a .btflut file (LRND, docs/btflut-format.md): the model's sizes (format version
/// 9: with its view features), each code's scale and bias, the light network's and the residual
/// network's parameters, then the codes three to an RGB PNG.
Bytes encodeLearnedModelChunk(const LearnedModel& m, std::uint32_t version);
/// The chunk read back: every count checked before anything is allocated by it, the decoder's
/// parameters as many as its sizes need and finite, the codes the reference's size, its
/// channels at most the reference's (`referenceChannels`).
Result<LearnedModel> decodeLearnedModelChunk(ByteReader& in, const ChunkSource& source, std::uint32_t version,
                                             int referenceChannels);
/// The kind in the registry (kind_chunk.h): HEAD's 3, its LRND chunk, from version 8 (9 for a
/// model of views); it predicts grey banks and rgb banks of a colour model (not lrgb's).
extern const KindChunk kLearnedModelChunk;

/// A learned model trained on every image (fitLearnedModel), of one camera or of rectified
/// views: its options.
class LearnedFit final : public PredictorFit {
public:
    explicit LearnedFit(LearnedOptions options) : m_options(std::move(options)) {}
    std::string family() const override { return "neural"; }
    std::string settings() const override;
    const FitKind& kind() const override;
    FitPointer trainedFor(double seconds, std::function<void(double)> progress) const override;
    Result<PredictorPointer> fit(const FitImages& in) const override;
    Result<UnmatchedModel> fitUnmatched(const FitImages& in) const override;
    const LearnedOptions& options() const { return m_options; }

private:
    LearnedOptions m_options;
};
FitPointer learnedFit(LearnedOptions options);
/// The kind in the fits' registry (predictor_fit.h): named by learnedModelNamed; auto's
/// candidate is neuralN of the bytes (at most kMaxCodes), trained for the bounds' time.
extern const FitKind kLearnedFit;

}  // namespace btflut
