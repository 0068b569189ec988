#pragma once
// K references blended per texel with the light's barycentric weights over a Delaunay
// triangulation of their lights (clamped outside its hull), on their 8-bit codes: the
// predictor of `bake --references K` (references.h picks them).

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/direction/triangulation.h"
#include "core/image/image.h"
#include "core/predict/predictor.h"

namespace btflut {

/// A reference's light and the image it was picked from.
struct ReferenceLight {
    std::string name;
    Direction light;
};

class ReferenceBlend final : public Predictor {
public:
    /// `references` 8-bit, grey or RGB, picked at `lights` (one each, no two alike).
    /// `perChannel`: RGB references matched per channel (rgb banks); else their grey, on the
    /// scale of the summed channel codes. `albedo` (lrgb: grey references and an RGB albedo)
    /// gives the chroma; empty for none.
    ReferenceBlend(std::vector<Image> references, std::vector<ReferenceLight> lights, bool perChannel, Image albedo);

    PredictorKind kind() const override { return PredictorKind::References; }
    std::string name() const override { return "references"; }
    double bytesPerTexel() const override;
    /// The references around the light (three at most), each weighted, per channel.
    std::size_t multiplyAdds() const override {
        return std::min<std::size_t>(m_references.size(), 3) * static_cast<std::size_t>(m_references.front().channels);
    }
    std::string description() const override {
        return std::to_string(m_references.size()) + " reference(s) blended per light";
    }
    PredictorPlanes planes() const override;
    /// Its weights at each light on a weight grid: the blend's barycentric weights there.
    EngineParts engineParts(const std::string& file) const override;
    void atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const override;
    void materialFields(nlohmann::json& predictor, const EngineParts& parts) const override;
    /// Each reference's weight (the blend's barycentric weights, clamped outside the references'
    /// hull) over a size x size grid of the equal-area light disk (node (i, j) at x = -1 + 2 i /
    /// (size - 1), y likewise; beyond the horizon, the horizon's), [node][reference]: for shaders
    /// that blend per fragment (curved surfaces, point lights) and read the weights bilinearly.
    std::vector<float> weightGrid(int size) const;
    std::vector<std::string> shaderDefines() const override;
    std::vector<ShaderValues> shaderValues(const PredictorFrame& frame) const override;
    PredictorFrame frameAt(Direction light, Direction view) const override;
    std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const override;
    void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const override;
    void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                    std::vector<std::uint64_t>& counts) const override {
        countCodesOf(*this, frame, texels, channel, counts);
    }

    const std::vector<Image>& references() const { return m_references; }
    const std::vector<ReferenceLight>& lights() const { return m_lights; }
    /// Over the references' lights' disk points: the blend's weights.
    const Triangulation& triangulation() const { return m_triangulation; }
    const Image& albedo() const { return m_albedo; }  ///< lrgb's; empty for none

private:
    std::vector<Image> m_references;
    std::vector<ReferenceLight> m_lights;
    Triangulation m_triangulation;
    Image m_albedo;
    std::vector<std::vector<std::int32_t>> m_referenceCodes;  // [reference][texel * channels + c]
};

}  // namespace btflut
