#include "core/predict/model_predictor.h"

#include <algorithm>
#include <sstream>

#include "core/check.h"

namespace btflut {

// Grey: one channel's codes (a grey model without albedo), or the sum of three.
ModelPredictor::ModelPredictor(LightModel model, bool perChannel)
    : Predictor(perChannel ? 3 : 1, perChannel || (model.albedo.empty() && model.channels == 1) ? 255 : 765),
      m_model(std::move(model)) {
    BTFLUT_CHECK(!m_model.empty());
}

std::string ModelPredictor::description() const {
    std::ostringstream out;
    out << name() << " (" << bytesPerTexel() << " bytes per texel), relit per light";
    return out.str();
}

PredictorPlanes ModelPredictor::planes() const {
    const LightModel& m = m_model;
    const auto P = static_cast<std::size_t>(m.planes);
    PredictorPlanes out;
    // 4-bit codes n are stored as 17 n (0 .. 255): value = (n - b) s = (17 n - 17 b) s / 17.
    auto widen = [&](std::size_t p) { return m.maxCode(static_cast<int>(p)) == 255 ? 1 : 17; };
    for (std::size_t p = 0; p < P; ++p) {
        out.scale.push_back(m.scale[p] / static_cast<float>(widen(p)));
        out.bias.push_back(m.bias[p] * static_cast<float>(widen(p)));
    }
    for (std::size_t first = 0; first < P; first += 4) {
        Image layer(m.width, m.height, 4);
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 4 && first + c < P; ++c)
                layer.samples[i * 4 + c] =
                    static_cast<float>(m.coefficients[i * P + first + c] * widen(first + c)) / 255.f;
        out.layers.push_back(std::move(layer));
    }
    if (!m.albedo.empty()) {
        out.albedo = Image(m.width, m.height, 3);
        std::transform(m.albedo.begin(), m.albedo.end(), out.albedo.samples.begin(),
                       [](std::uint8_t b) { return b / 255.f; });
    }
    return out;
}

std::vector<std::string> ModelPredictor::shaderDefines() const {
    const std::string layers = std::to_string((m_model.planes + 3) / 4);
    std::vector<std::string> d{"PREDICT_MODEL", "PREDICT_MODEL_LAYERS " + layers,
                               "PREDICT_MODEL_WIDE " + std::to_string(m_model.wide),
                               "PREDICT_MODEL_CHANNELS " + std::to_string(m_model.channels)};
    if (!m_model.albedo.empty()) d.insert(d.end(), {"PREDICT_MODEL_ALBEDO", "PREDICT_ALBEDO_LAYER " + layers});
    return d;
}

std::vector<ShaderValues> ModelPredictor::shaderValues(const PredictorFrame& frame) const {
    // btflut.glsl's BtflutModelFrame: per layer of four planes and per channel ([layer * 3 +
    // channel]) the planes' weights, the offsets, the scale (LightModelFixed; the CPU's twin:
    // predictFixed).
    const auto P = static_cast<std::size_t>(m_model.planes), C = static_cast<std::size_t>(m_model.channels);
    std::vector<float> weights((P + 3) / 4 * 3 * 4, 0.f);
    for (std::size_t q = 0; q < P; ++q)
        for (std::size_t c = 0; c < C; ++c)
            weights[((q / 4) * 3 + c) * 4 + q % 4] = static_cast<float>(frame.model.weights[q * C + c]);
    const LightModelFixed& f = frame.model;
    return {{"predictModel.weights", 4, std::move(weights)},
            {"predictModel.offset",
             3,
             {static_cast<float>(f.offset[0]), static_cast<float>(f.offset[1]), static_cast<float>(f.offset[2])}},
            {"predictModel.scale", 1, {f.scale}}};
}

PredictorFrame ModelPredictor::frameAt(Direction light, Direction /*view: one camera*/) const {
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
