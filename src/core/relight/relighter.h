#pragma once
// Relighting a bank's reference(s) for one light: what the renderer's shader does and its
// CPU twin. For a classic bank (one reference, one region) the frame is the bank's LUT for
// the light (LutBank::lookup) and applying it is applyLuts. A bank that makes its LUTs at run
// time (LutBank::Prediction: several references, regions, lrgb) is relit in two steps:
//   1. predict: the references around the light (a Delaunay triangle of their lights,
//      clamped outside their hull) are blended per texel with barycentric weights, on their
//      codes; or the bank's light model (light_model.h: ptm, hsh, rbf, bln) is evaluated
//      for the light;
//   2. match: per region, the prediction's exact distribution over the region's sample
//      texels is counted, and ONE LUT maps it onto the target distribution at the light (the
//      nodes' quantile functions blended, as LutBank::lookup blends LUTs); with
//      Prediction::match below 1, onto the blend of that target with the prediction's own.
// So the histogram is the target's, as with one reference, while shadows and highlights come
// from the references lit most like the light. Colour: grey blends RGB references and keeps
// the blend's chroma; rgb matches each channel; lrgb blends grey references and takes the
// chroma of the albedo.
//
//   Relighter relighter(bank);                        // per-texel codes, once per bank
//   RelightFrame frame = relighter.frame(light);      // per light change: weights and LUTs
//   Image image = relighter.apply(frame, true);       // the CPU twin of the shader

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/predict/predictor.h"

namespace btflut {

/// A light's frame: the predictor's integers there (PredictorFrame: its weights) and the LUTs.
struct RelightFrame : PredictorFrame {
    Direction light, view;    ///< what the frame is for
    std::vector<float> luts;  ///< regions x channels x entries
    /// Of the target (LutBank::lookup): the worse of the light's and the view's.
    Provenance provenance = Provenance::Measured, lightProvenance = Provenance::Measured,
               viewProvenance = Provenance::Measured;
    BankLookup target;  ///< the bank's lookup: LUTs, or quantile functions (blend)
};

class Relighter {
public:
    explicit Relighter(const LutBank& bank);

    /// The blend and the LUTs for a light (and view); with `interpolate` false, the target of
    /// the nearest node.
    RelightFrame frame(Direction light, Direction view = {}, bool interpolate = true) const;

    /// A bank with a predictor: the frame with its LUTs read bilinearly from the bank's match
    /// grid (LutBank::matchGridLuts; made here when the bank of one view has none), as an
    /// engine reads the exported grid: no counting of the prediction when the light moves. A
    /// bank of views (a view-dependent predictor) blends its layers' grids as lookup blends
    /// their nodes, or with `layer` reads that layer's alone (as an engine reads the nearest).
    RelightFrame gridFrame(Direction light, Direction view = {}, std::optional<std::size_t> layer = {}) const;

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

    /// How far a light's LUT moves the prediction towards the target: 1 at a measured light
    /// (its photograph's histogram, exactly), the bank's Prediction::match from half the median
    /// spacing of the measured lights on (matchRampRadius), smoothly between (smoothstep of
    /// the equal-area disk distance to the nearest measured light), so nothing jumps. A bank of
    /// views measures (light, view) pairs: the distance is to the nearest pair, its light's and
    /// its view's disk distances combined.
    float matchAt(Direction light, Direction view = {}) const;
    /// That half spacing, on the equal-area disk (0 for a bank matched fully: no ramp).
    float matchRampRadius() const { return m_rampRadius; }

private:
    /// The prediction's part of a frame (blend weights or the model's integers), no LUTs.
    RelightFrame predictionFrame(Direction light, Direction view) const;
    std::vector<float> lutsFor(const RelightFrame& frame, const std::vector<float>& quantiles) const;
    /// The identity's LUT on the predicted codes' scale (code q read at (q + 1) / (codes + 1)
    /// gives q / codes): what a match of 0 leaves.
    float identity(float v) const;
    /// A region's and channel's predicted codes as counts (code q at index q + 1, value
    /// (q + 1) / (codes + 1): every cell inside [0, 1]).
    LevelCounts predictedCounts(const RelightFrame& frame, std::size_t region, int channel) const;
    /// A texel's predicted code, 0 .. codes: the predictor's.
    std::size_t predictedCode(const RelightFrame& frame, std::size_t texel, int channel) const {
        return m_predictor->code(frame, texel, channel);
    }

    const LutBank& m_bank;
    const Predictor* m_predictor = nullptr;                  // banks that make their LUTs: the bank's
    int m_codes = 255;                                       // codes of a predicted value (765 for the grey of RGB8)
    int m_counted = 1;                                       // channels counted: 3 for rgb, else 1 (grey)
    std::vector<std::vector<std::uint32_t>> m_regionTexels;  // sample texels of each region
    std::vector<DiskPoint> m_measured;                       // the measured lights (matchAt)
    std::vector<DiskPoint> m_measuredViews;                  // ... and their views (a bank of views)
    float m_rampRadius = 0;
    /// Corrections (LutBank::Prediction::Target::Corrections): the bank's nodes with, instead of
    /// their targets, the LUTs from the prediction at their lights to their targets.
    std::shared_ptr<const LutBank> m_corrections;
    /// For a bank read without its match grid (older files): the grid, made on first use.
    mutable std::shared_ptr<const LutBank> m_gridBank;
};

/// The reference image with the LUT for (light, view) applied to every pixel (see
/// applyLuts), dithered unless `dither` is false; for banks that make their LUTs at run time,
/// the references blended and matched (Relighter).
Image relight(const LutBank& bank, Direction light, Direction view = {}, bool dither = true);

/// A bank with a predictor: the codes of a predicted value, 255 (a channel) or 765 (the grey of
/// RGB8: three channels' codes summed); its match LUTs read code q at (q + 1) / (codes + 1).
int predictionCodes(const LutBank& bank);

/// Half the median distance from a measured light of `bank` to its nearest neighbour on the
/// equal-area disk: how far from a measured light the match strength ramps down to the bank's
/// (Relighter::matchAt).
float matchRampRadius(const LutBank& bank);

/// Fills every layer's match grid of a bank with a predictor (LutBank::matchGridLuts): at each
/// grid node the LUT from the prediction at the node's light (beyond the horizon: at the
/// horizon) to the target there, made as Relighter::frame makes it. Bake calls it; so must
/// whatever changes a bank's targets or predictor afterwards (model fill).
void bakeMatchGrid(LutBank& bank, int threads = 0);

}  // namespace btflut
