#include "core/predict/reference_blend.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/io/json_text.h"

namespace btflut {

namespace {
Triangulation overLights(const std::vector<ReferenceLight>& lights) {
    std::vector<DiskPoint> points;
    for (const ReferenceLight& l : lights) points.push_back(toDisk(l.light));
    return Triangulation(std::move(points));
}
}  // namespace

ReferenceBlend::ReferenceBlend(std::vector<Image> references, std::vector<ReferenceLight> lights, bool perChannel,
                               Image albedo)
    : Predictor(perChannel ? 3 : 1, perChannel ? 255 : 255 * references.at(0).channels),
      m_references(std::move(references)),
      m_lights(std::move(lights)),
      m_triangulation(overLights(m_lights)),
      m_albedo(std::move(albedo)) {
    BTFLUT_CHECK(m_references.size() == m_lights.size());
    BTFLUT_CHECK(m_references.front().bitDepth == 8);  // the blend's codes are 8-bit (bakeBank's blendForm)
    const int counted = channels();
    auto code = [](float v) { return static_cast<std::int32_t>(std::lround(v * 255.f)); };
    for (const Image& reference : m_references) {
        std::vector<std::int32_t> codes(reference.pixelCount() * static_cast<std::size_t>(counted));
        for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
            const float* p = &reference.samples[i * static_cast<std::size_t>(reference.channels)];
            if (counted == 3 || reference.channels == 1) {
                for (int c = 0; c < counted; ++c) codes[i * counted + c] = code(p[c]);
            } else {  // the grey of RGB on its exact code scale: the sum of the channel codes
                codes[i] = code(p[0]) + code(p[1]) + code(p[2]);
            }
        }
        m_referenceCodes.push_back(std::move(codes));
    }
}

double ReferenceBlend::bytesPerTexel() const {
    return static_cast<double>(m_references.size()) * m_references.front().channels +
           (m_albedo.samples.empty() ? 0 : 3);
}

PredictorPlanes ReferenceBlend::planes() const {
    PredictorPlanes out;
    for (const Image& reference : m_references) {
        Image layer(reference.width, reference.height, 4);  // RGBA8: grey in R, G and B, alpha opaque
        const auto channels = static_cast<std::size_t>(reference.channels);
        for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
            for (std::size_t c = 0; c < 3; ++c)
                layer.samples[i * 4 + c] =
                    std::round(reference.samples[i * channels + std::min(c, channels - 1)] * 255.f) / 255.f;
            layer.samples[i * 4 + 3] = 1.f;
        }
        out.layers.push_back(std::move(layer));
    }
    out.albedo = m_albedo;
    return out;
}

std::vector<std::string> ReferenceBlend::shaderDefines() const {
    std::vector<std::string> d{"PREDICT_FETCHES " + std::to_string(std::min<std::size_t>(m_references.size(), 3))};
    if (!m_albedo.samples.empty())
        d.insert(d.end(), {"PREDICT_ALBEDO_CHROMA", "PREDICT_ALBEDO_LAYER " + std::to_string(m_references.size())});
    return d;
}

std::vector<ShaderValues> ReferenceBlend::shaderValues(const PredictorFrame& frame) const {
    // The references around the light and their weights (PREDICT_FETCHES of each; unused ones 0).
    const std::size_t fetches = std::min<std::size_t>(m_references.size(), 3);
    std::vector<float> layers(fetches, 0.f), weights(fetches, 0.f);
    for (std::size_t k = 0; k < static_cast<std::size_t>(frame.count); ++k) {
        layers[k] = static_cast<float>(frame.references[k]);
        weights[k] = static_cast<float>(frame.weights[k]);
    }
    return {{"blendLayer", 1, std::move(layers), true}, {"blendWeight", 1, std::move(weights)}};
}

PredictorFrame ReferenceBlend::frameAt(Direction light, Direction /*view: one camera*/) const {
    PredictorFrame frame;
    frame.count = 0;
    // Barycentric weights in 1 / kWeightUnit; the largest takes the rounding so they sum to it.
    const Weights w = m_triangulation.weightsAt(toDisk(light));
    std::int32_t total = 0;
    std::size_t largest = 0;
    for (int k = 0; k < w.count; ++k) {
        const auto weight = static_cast<std::int32_t>(std::lround(w.weight[static_cast<std::size_t>(k)] * kWeightUnit));
        if (weight <= 0) continue;
        if (weight > frame.weights[largest] || frame.count == 0) largest = static_cast<std::size_t>(frame.count);
        frame.references[static_cast<std::size_t>(frame.count)] = w.index[static_cast<std::size_t>(k)];
        frame.weights[static_cast<std::size_t>(frame.count)] = weight;
        total += weight;
        ++frame.count;
    }
    frame.weights[largest] += kWeightUnit - total;
    return frame;
}

std::size_t ReferenceBlend::code(const PredictorFrame& frame, std::size_t texel, int channel) const {
    std::int64_t sum = 0;
    for (int k = 0; k < frame.count; ++k)
        sum += std::int64_t{frame.weights[static_cast<std::size_t>(k)]} *
               m_referenceCodes[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])]
                               [texel * channels() + channel];
    return roundedCode(sum, codes());
}

void ReferenceBlend::colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const {
    if (!m_albedo.samples.empty()) {  // lrgb: the albedo's chroma
        std::copy_n(&m_albedo.samples[texel * 3], 3, rgb);
        return;
    }
    for (int c = 0; c < 3; ++c) {  // the blend's own (RGB references)
        rgb[c] = 0;
        for (int k = 0; k < frame.count; ++k)
            rgb[c] += static_cast<float>(frame.weights[static_cast<std::size_t>(k)]) / kWeightUnit *
                      m_references[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])]
                          .samples[texel * 3 + c];
    }
}

std::vector<float> ReferenceBlend::weightGrid(int size) const {
    BTFLUT_CHECK(size >= 2);
    const std::size_t k = m_references.size();
    std::vector<float> grid(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * k, 0.f);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const Weights w = m_triangulation.weightsAt(toDisk(fromDisk(diskGridPoint(i, j, size))));
            float* node =
                &grid[(static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)) * k];
            for (int n = 0; n < w.count; ++n)
                node[static_cast<std::size_t>(w.index[static_cast<std::size_t>(n)])] +=
                    static_cast<float>(w.weight[static_cast<std::size_t>(n)]);
        }
    return grid;
}

EngineParts ReferenceBlend::engineParts(const std::string&) const {
    EngineParts out;
    out.planes = static_cast<int>(m_references.size());
    out.channels = m_references.front().channels;
    out.weights = out.planes;
    out.weightGridSize = kEngineWeightGrid;
    out.weightGrid =
        weightsInLayers(weightGrid(kEngineWeightGrid), static_cast<std::size_t>(out.weights), kEngineWeightGrid);
    return out;
}

// The references' images and lights, and lrgb's albedo.
void ReferenceBlend::atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const {
    if (!m_albedo.samples.empty()) blend["albedo"] = texture("albedo", m_albedo);
    for (std::size_t k = 0; k < m_references.size(); ++k)
        blend["references"].push_back({{"file", texture("reference-" + std::to_string(k), m_references[k])},
                                       {"light", directionJson(m_lights[k].light)}});
}

// A reference to an image; the weight grid's rows its blend weights.
void ReferenceBlend::materialFields(nlohmann::json& predictor, const EngineParts&) const {
    predictor["images_layout"] = "one reference per image (RGB; a grey one in R, G and B)";
    predictor["weights"]["row"] = "one weight per reference";
}

}  // namespace btflut
