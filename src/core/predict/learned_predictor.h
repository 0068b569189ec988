#pragma once
// A learned model (learned_model.h) as a bank's predictor: per texel its codes, decoded by the
// bank's network at each light. A frame decodes every texel once (the network's cost per
// texel is LearnedModel::decoderCost multiply-adds), so a texel's code is a lookup.

#include "core/predict/learned_model.h"
#include "core/predict/predictor.h"

namespace btflut {

class LearnedPredictor final : public Predictor {
public:
    /// `perChannel`: its RGB matched per channel (rgb banks); else its grey, on the scale of
    /// the summed channel codes when it has colour.
    LearnedPredictor(LearnedModel model, bool perChannel);

    std::string name() const override { return learnedModelName(m_model); }
    double bytesPerTexel() const override { return m_model.codes; }
    std::string description() const override;
    PredictorPlanes planes() const override;
    std::vector<std::string> shaderDefines() const override;
    std::vector<ShaderValues> shaderValues(const PredictorFrame& frame) const override;
    PredictorFrame frameAt(Direction light) const override;
    std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const override;
    void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const override;
    void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                    std::vector<std::uint64_t>& counts) const override {
        countCodesOf(*this, frame, texels, channel, counts);
    }

    const LearnedModel& model() const { return m_model; }

private:
    LearnedModel m_model;
    bool m_perChannel;
};

}  // namespace btflut
