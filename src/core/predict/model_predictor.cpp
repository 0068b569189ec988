#include "core/predict/model_predictor.h"

#include "core/check.h"

namespace btflut {

// Grey: one channel's codes (a grey model without albedo), or the sum of three.
ModelPredictor::ModelPredictor(const LightModel& model, bool perChannel)
    : Predictor(perChannel ? 3 : 1, perChannel || (model.albedo.empty() && model.channels == 1) ? 255 : 765),
      m_model(model) {
    BTFLUT_CHECK(!model.empty());
}

PredictorFrame ModelPredictor::frameAt(Direction light) const {
    PredictorFrame frame;
    frame.count = 0;
    frame.model = lightModelFixed(m_model, light);
    return frame;
}

std::size_t ModelPredictor::code(const PredictorFrame& frame, std::size_t texel, int channel) const {
    const std::array<std::int64_t, 3> c = predictFixed(m_model, frame.model, texel);
    return roundedCode(channels() == 3 ? c[static_cast<std::size_t>(channel)] : c[0] + c[1] + c[2], codes());
}

void ModelPredictor::colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const {
    const std::array<std::int64_t, 3> c = predictFixed(m_model, frame.model, texel);
    for (std::size_t k = 0; k < 3; ++k) rgb[k] = static_cast<float>(c[k]) / (255.f * kWeightUnit);
}

}  // namespace btflut
