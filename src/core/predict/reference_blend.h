#pragma once
// K references blended per texel with the light's barycentric weights over a Delaunay
// triangulation of their lights (clamped outside its hull), on their 8-bit codes: the
// predictor of `bake --references K` (references.h picks them).

#include <cstdint>
#include <vector>

#include "core/direction/triangulation.h"
#include "core/image/image.h"
#include "core/predict/predictor.h"

namespace btflut {

class ReferenceBlend final : public Predictor {
public:
    /// `references` 8-bit, grey or RGB, and `lights` over their lights' disk points, both
    /// outliving the predictor. `perChannel`: RGB references matched per channel (rgb
    /// banks); else their grey, on the scale of the summed channel codes. `albedo` (lrgb: grey
    /// references and an RGB albedo) gives the chroma, or null.
    ReferenceBlend(const std::vector<Image>& references, const Triangulation& lights, bool perChannel,
                   const Image* albedo);

    std::string name() const override { return "references"; }
    double bytesPerTexel() const override;
    PredictorPlanes planes() const override;
    std::vector<std::string> shaderDefines() const override;
    PredictorFrame frameAt(Direction light) const override;
    std::size_t code(const PredictorFrame& frame, std::size_t texel, int channel) const override;
    void colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const override;
    void countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                    std::vector<std::uint64_t>& counts) const override {
        countCodesOf(*this, frame, texels, channel, counts);
    }

private:
    const std::vector<Image>& m_references;
    const Triangulation& m_lights;
    const Image* m_albedo;
    std::vector<std::vector<std::int32_t>> m_referenceCodes;  // [reference][texel * channels + c]
};

}  // namespace btflut
