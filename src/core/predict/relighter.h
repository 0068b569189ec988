#pragma once
// Relighting a bank's reference(s) for one light: what the renderer's shader does and its
// CPU twin. For a classic bank (one reference, one region) the frame is the bank's LUT for
// the light (LutBank::lookup) and applying it is applyLuts. A bank that makes its LUTs at run
// time (LutBank::Blend: several references, regions, lrgb) is relit in two steps:
//   1. predict: the references around the light (a Delaunay triangle of their lights,
//      clamped outside their hull) are blended per texel with barycentric weights, on their
//      codes; or the bank's PTM is evaluated for the light (--predictor ptm);
//   2. match: per region, the blend's exact distribution over the region's sample texels is
//      counted, and ONE LUT maps it onto the target distribution at the light (the nodes'
//      quantile functions blended, as LutBank::lookup blends LUTs).
// So the histogram is the target's, as with one reference, while shadows and highlights come
// from the references lit most like the light. Colour: grey blends RGB references and keeps
// the blend's chroma; rgb matches each channel; lrgb blends grey references and takes the
// chroma of the albedo.
//
//   Relighter relighter(bank);                        // per-texel codes, once per bank
//   RelightFrame frame = relighter.frame(light);      // per light change: weights and LUTs
//   Image image = relighter.apply(frame, true);       // the CPU twin of the shader

#include <array>
#include <vector>

#include "core/bank/lut_bank.h"

namespace btflut {

/// Blends are exact integer arithmetic, so that the CPU and a GPU (whose float sums of
/// integers below 2^24 are exact, fused or not) get the same codes: reference weights are
/// integers summing to kWeightUnit, applied to the references' 8-bit codes.
constexpr int kWeightUnit = 4096;

/// The PTM predictor's per-light integers (from ptmWeights): a texel's fixed-point luminance
/// L = floor((offset + sum_k byte_k weights[k]) * scale), luminance * kWeightUnit; the sum
/// stays below 2^23, scale is a power of two.
struct PtmFixed {
    std::array<std::int32_t, Ptm::kTerms> weights{};
    std::int32_t offset = 0;
    float scale = 1;
};
PtmFixed ptmFixed(const Ptm& ptm, Direction light);

struct RelightFrame {
    Direction light;                     ///< what the frame is for
    int count = 1;                       ///< references blended, 1 to 3 (0 for the PTM predictor)
    std::array<int, 3> references{0, 0, 0};
    std::array<std::int32_t, 3> weights{kWeightUnit, 0, 0};  ///< in 1 / kWeightUnit, summing to kWeightUnit
    PtmFixed ptm;                        ///< the PTM predictor's
    std::vector<float> luts;             ///< regions x channels x entries
    /// Of the target (LutBank::lookup): the worse of the light's and the view's.
    Provenance provenance = Provenance::Measured, lightProvenance = Provenance::Measured,
               viewProvenance = Provenance::Measured;
    BankLookup target;                   ///< the bank's lookup: LUTs, or quantile functions (blend)
};

class Relighter {
public:
    explicit Relighter(const LutBank& bank);

    /// The blend and the LUTs for a light (and view); with `interpolate` false, the target of
    /// the nearest node.
    RelightFrame frame(Direction light, Direction view = {}, bool interpolate = true) const;

    /// The relit image at the reference's size; dithered (lut.h) unless `dither` is false.
    Image apply(const RelightFrame& frame, bool dither) const;

    /// The alternative that blending per-reference LUTs gives (each reference matched to the
    /// target, the results blended): measured against blend-then-match by `btflut eval`; the
    /// blend of matched images does not keep the target's histogram.
    Image applyBlendingLuts(Direction light, Direction view, bool dither) const;

    /// One code of the values the LUTs read. A predicted code q is read at (q + 1) /
    /// (codes + 1), the top of its cell [q, q + 1) / (codes + 1): unlike a classic
    /// reference's code 0, whose cell lies below [0, 1], every cell is inside, so dithering
    /// splits black and white too (predictors make spikes there: a PTM clips).
    float inputCode() const { return 1.f / static_cast<float>(m_codes + 1); }

private:
    std::vector<float> lutsFor(const RelightFrame& frame, const std::vector<float>& quantiles) const;
    /// The PTM predictor: a texel's channels times 255 * kWeightUnit, clipped (Ptm::render in
    /// fixed point).
    std::array<std::int64_t, 3> ptmChannels(const PtmFixed& ptm, std::size_t texel) const;
    /// A texel's predicted code, 0 .. codes: the blend, or the PTM's grey.
    std::size_t predictedCode(const RelightFrame& frame, std::size_t texel, int channel) const;
    bool usesPtm() const { return m_bank.blend.predictor == LutBank::Blend::Predictor::Ptm; }

    const LutBank& m_bank;
    int m_codes = 255;                       // codes of a blended value (765 for the grey of RGB8)
    int m_counted = 1;                       // channels counted: 3 for rgb, else 1 (grey)
    std::vector<std::vector<std::int32_t>> m_referenceCodes;  // [reference][texel * counted + c]
    std::vector<std::vector<std::uint32_t>> m_regionTexels;    // sample texels of each region
};

}  // namespace btflut
