#pragma once
// A linear light model (light_model.h: ptm, hsh, rbf, bln) as a bank's predictor: its per-light
// integers and each texel's fixed-point prediction, what an engine reads of it, and its chunk of
// the .btflut file (LMDL).

#include "core/io/byte_stream.h"
#include "core/predict/chunk_planes.h"
#include "core/predict/kind_chunk.h"
#include "core/predict/light_model.h"
#include "core/predict/predictor.h"
#include "core/predict/predictor_fit.h"

namespace btflut {

class ModelPredictor final : public Predictor {
public:
    /// `perChannel`: its RGB matched per channel (rgb banks); else its grey, on the scale of
    /// the summed channel codes when it has colour.
    ModelPredictor(LightModel model, bool perChannel);

    PredictorKind kind() const override { return PredictorKind::Model; }
    std::string name() const override { return lightModelName(m_model); }
    double bytesPerTexel() const override { return m_model.bytesPerTexel(); }
    std::size_t multiplyAdds() const override { return m_model.multiplyAdds(); }
    std::string description() const override;
    PredictorPlanes planes() const override;
    /// ptm and hsh: their weights in closed form (btflut.glsl); rbf and bln: on a weight grid.
    EngineParts engineParts(const std::string& file) const override;
    void atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const override;
    void materialFields(nlohmann::json& predictor, const EngineParts& parts) const override;
    std::vector<std::string> shaderDefines() const override;
    std::vector<ShaderValues> shaderValues(const PredictorFrame& frame) const override;
    PredictorFrame frameAt(Direction light, Direction view) const override;
    std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const override;
    void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const override;
    void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                    std::vector<std::uint64_t>& counts) const override {
        countCodesOf(*this, frame, texels, channel, counts);
    }

    const LightModel& model() const { return m_model; }

private:
    LightModel m_model;
};

/// Its chunk of a .btflut file (LMDL, docs/btflut-format.md): the model's description, its
/// per-light table, then its planes three to an RGB PNG and, in the LRGB layout, the albedo.
Bytes encodeLightModelChunk(const LightModel& m);
/// The chunk read back: every count checked before anything is allocated by it, every number
/// finite, the planes and albedo the reference's size, its colour the reference's
/// (`referenceChannels`; an albedo on a grey reference too, as a bank's PTM had).
Result<LightModel> decodeLightModelChunk(ByteReader& in, const ChunkSource& source, int referenceChannels);
/// The kind in the registry (kind_chunk.h): HEAD's 2, its LMDL chunk, from version 5; it
/// predicts grey and rgb banks (not lrgb's, whose albedo is the references').
extern const KindChunk kLightModelChunk;

/// A light model fitted to every image (fitLightModel): its options.
class LightModelFit final : public PredictorFit {
public:
    explicit LightModelFit(LightModelOptions options) : m_options(std::move(options)) {}
    std::string family() const override { return lightBasisName(m_options.basis); }
    std::string settings() const override;
    const FitKind& kind() const override;
    Result<PredictorPointer> fit(const FitImages& in) const override;
    Result<UnmatchedModel> fitUnmatched(const FitImages& in) const override;
    const LightModelOptions& options() const { return m_options; }

private:
    LightModelOptions m_options;
};
FitPointer lightModelFit(LightModelOptions options);
/// The kind in the fits' registry (predictor_fit.h): named by lightModelNamed; auto's candidates
/// ptm, hsh2 and hsh3 (with an albedo for colour), and rbf and bln of the bytes, plain and packed.
extern const FitKind kLightModelFit;

}  // namespace btflut
