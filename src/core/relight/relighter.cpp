#include "core/relight/relighter.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/parallel.h"
#include "core/predict/reference_blend.h"

namespace btflut {

namespace {

// The measured lights of the bank's first view layer on the equal-area disk.
std::vector<DiskPoint> measuredDiskPoints(const LutBank& bank) {
    std::vector<DiskPoint> lights;
    for (std::size_t n = 0; n < bank.layers.at(0).measuredNodes; ++n)
        lights.push_back(toDisk(bank.layers[0].nodes[n].light));
    return lights;
}

// Half the median distance from a light to its nearest neighbour (matchRampRadius).
float rampRadius(const std::vector<DiskPoint>& lights) {
    if (lights.size() < 2) return 0.25f;  // one light: a quarter of the disk's radius
    std::vector<double> nearest;
    for (const DiskPoint& p : lights) {
        double d = 1e30;
        for (const DiskPoint& q : lights)
            if (&p != &q) d = std::min(d, std::hypot(p.x - q.x, p.y - q.y));
        nearest.push_back(d);
    }
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(nearest.size() / 2), nearest.end());
    return static_cast<float>(std::max(nearest[nearest.size() / 2] / 2, 1e-3));
}

// Predicted codes counted at their top-of-cell values (Relighter::predictedCounts) as
// counts at their own values q / codes.
LevelCounts ownValues(const LevelCounts& counts) {
    LevelCounts own;
    own.counts.assign(counts.counts.begin() + 1, counts.counts.end());
    return own;
}

}  // namespace

Relighter::Relighter(const LutBank& bank) : m_bank(bank) {
    if (!bank.makesLuts()) return;
    const LutBank::Prediction& blend = bank.prediction;
    m_regionTexels.resize(static_cast<std::size_t>(blend.regions));
    for (std::size_t i = 0; i < blend.mask.inside.size(); ++i)
        if (blend.mask.inside[i])
            m_regionTexels[blend.labels.empty() ? 0 : blend.labels[i]].push_back(static_cast<std::uint32_t>(i));
    m_predictor = &bank.predictor();
    m_counted = m_predictor->channels();  // rgb: each channel matched apart
    m_codes = m_predictor->codes();       // the grey of RGB8 on its channels' codes' scale: 765
    if (blend.match < 1) {                // matchAt's ramp; a bank matched fully needs none
        m_measured = measuredDiskPoints(bank);
        m_rampRadius = rampRadius(m_measured);
        if (m_predictor->viewDependent()) {  // every layer's measured (light, view) pairs
            m_measured.clear();
            for (const ViewLayer& layer : bank.layers)
                for (std::size_t n = 0; n < layer.measuredNodes; ++n) {
                    m_measured.push_back(toDisk(layer.nodes[n].light));
                    m_measuredViews.push_back(toDisk(layer.view));
                }
        }
    }
    if (blend.target == LutBank::Prediction::Target::Corrections) {
        // Each node's LUT from the prediction at its light to its target, in a bank of the
        // same nodes (its lookups blend them as a classic bank's).
        auto corrections = std::make_shared<LutBank>(bank.sameDirections());
        corrections->prediction.regions = blend.regions;
        corrections->prediction.quantiles = bank.entries;  // its node values: regions x channels x entries
        const auto samples = static_cast<std::size_t>(blend.quantiles);
        for (std::size_t l = 0; l < bank.layers.size(); ++l) {
            const ViewLayer& layer = bank.layers[l];
            ViewLayer& copy = corrections->layers[l];
            for (std::size_t n = 0; n < layer.nodes.size(); ++n) {
                const RelightFrame f = predictionFrame(layer.nodes[n].light, layer.view);
                const float* targets = &layer.nodeLuts[n * bank.nodeLength()];
                for (std::size_t r = 0; r < m_regionTexels.size(); ++r)
                    for (int c = 0; c < m_counted; ++c) {
                        const float* q =
                            targets + (r * static_cast<std::size_t>(m_counted) + static_cast<std::size_t>(c)) * samples;
                        const Lut lut = matchToQuantiles(predictedCounts(f, r, c), std::span(q, samples), bank.entries);
                        copy.nodeLuts.insert(copy.nodeLuts.end(), lut.values.begin(), lut.values.end());
                    }
            }
        }
        m_corrections = std::move(corrections);
    }
}

RelightFrame Relighter::frame(Direction light, Direction view, bool interpolate) const {
    RelightFrame frame = m_bank.makesLuts() ? predictionFrame(light, view) : RelightFrame{};
    frame.light = light;
    frame.view = view;
    frame.target = m_bank.lookup(light, view, interpolate);
    const BankLookup& target = frame.target;
    frame.provenance = target.provenance;
    frame.lightProvenance = target.lightProvenance;
    frame.viewProvenance = target.viewProvenance;
    if (!m_bank.makesLuts()) {
        frame.luts = target.values;
        return frame;
    }
    if (m_corrections) {
        frame.luts = m_corrections->lookup(light, view, interpolate).values;
        if (const float match = matchAt(light, view); match < 1) {
            const auto entries = static_cast<std::size_t>(m_bank.entries);
            for (std::size_t k = 0; k < frame.luts.size(); ++k) {
                const float v = static_cast<float>(k % entries) / static_cast<float>(entries - 1);
                frame.luts[k] = match * frame.luts[k] + (1 - match) * identity(v);
            }
        }
        return frame;
    }
    frame.luts = lutsFor(frame, target.values);
    return frame;
}

RelightFrame Relighter::gridFrame(Direction light, Direction view, std::optional<std::size_t> layer) const {
    BTFLUT_CHECK(m_bank.makesLuts() && (m_bank.layers.size() == 1 || !m_bank.layers[0].matchGridLuts.empty()));
    RelightFrame frame = predictionFrame(light, view);
    frame.target =
        m_bank.lookup(light, view);  // what the frame says of the target (a viewer plots it): no per-texel work
    frame.provenance = frame.target.provenance;
    frame.lightProvenance = frame.target.lightProvenance;
    frame.viewProvenance = frame.target.viewProvenance;
    if (!m_bank.layers[0].matchGridLuts.empty()) {
        frame.luts = layer ? m_bank.matchGridLookup(light, *layer) : m_bank.matchGridLookup(light, view);
        return frame;
    }
    static std::mutex making;
    std::shared_ptr<const LutBank> grid;
    {
        std::lock_guard lock(making);
        if (!m_gridBank) {  // a bank read without its grid: made once, here
            LutBank whole = m_bank;
            bakeMatchGrid(whole);
            auto copy = std::make_shared<LutBank>(whole.sameDirections());
            copy->prediction.regions = m_bank.prediction.regions;
            copy->layers.resize(1);  // the first view's grid, which matchGridLookup(light) reads
            copy->layers[0].matchGridLuts = std::move(whole.layers[0].matchGridLuts);
            m_gridBank = std::move(copy);
        }
        grid = m_gridBank;
    }
    frame.luts = grid->matchGridLookup(light);
    return frame;
}

int predictionCodes(const LutBank& bank) {
    BTFLUT_CHECK(bank.makesLuts());
    return bank.predictor().codes();
}

void bakeMatchGrid(LutBank& bank, int threads) {
    BTFLUT_CHECK(bank.makesLuts());
    const Relighter relighter(bank);
    const auto cells = static_cast<std::size_t>(bank.gridSize) * static_cast<std::size_t>(bank.gridSize);
    const std::size_t length = bank.matchLength();
    for (ViewLayer& layer : bank.layers) {
        std::vector<std::uint16_t> grid(cells * length);
        parallelFor(cells, threads, [&](std::size_t cell) {
            const int i = static_cast<int>(cell % static_cast<std::size_t>(bank.gridSize)),
                      j = static_cast<int>(cell / static_cast<std::size_t>(bank.gridSize));
            // Beyond the horizon: the horizon's LUT (fromDisk pulls the point onto it).
            const RelightFrame f = relighter.frame(fromDisk(bank.gridPoint(i, j)), layer.view);
            for (std::size_t k = 0; k < length; ++k)
                grid[cell * length + k] =
                    static_cast<std::uint16_t>(std::lround(std::clamp(f.luts[k], 0.f, 1.f) * 65535.0));
        });
        layer.matchGridLuts = std::move(grid);
    }
}

RelightFrame Relighter::predictionFrame(Direction light, Direction view) const {
    RelightFrame frame;
    static_cast<PredictorFrame&>(frame) = m_predictor->frameAt(light, view);
    frame.light = light;
    frame.view = view;
    return frame;
}

LevelCounts Relighter::predictedCounts(const RelightFrame& frame, std::size_t region, int channel) const {
    LevelCounts counts;
    counts.counts.assign(static_cast<std::size_t>(m_codes) + 2, 0);
    m_predictor->countCodes(frame, m_regionTexels[region], channel, counts.counts);
    return counts;
}

float Relighter::matchAt(Direction light, Direction view) const {
    const float match = m_bank.prediction.match;
    if (match >= 1 || m_measured.empty()) return match;
    const DiskPoint p = toDisk(light), v = toDisk(view);
    double nearest = 1e30;
    for (std::size_t k = 0; k < m_measured.size(); ++k) {
        const DiskPoint& q = m_measured[k];
        const double viewDistance =
            m_measuredViews.empty() ? 0 : std::hypot(v.x - m_measuredViews[k].x, v.y - m_measuredViews[k].y);
        nearest = std::min(nearest, std::hypot(p.x - q.x, p.y - q.y, viewDistance));
    }
    const double t = std::clamp(nearest / m_rampRadius, 0.0, 1.0), away = t * t * (3 - 2 * t);
    return static_cast<float>(1 - (1 - match) * away);
}

float Relighter::identity(float v) const {
    return std::clamp((v * static_cast<float>(m_codes + 1) - 1) / static_cast<float>(m_codes), 0.f, 1.f);
}

// Per region and channel: the prediction's codes over the region's sample texels, matched to
// the region's target quantile function (with a match below 1, to its blend with the
// prediction's own).
std::vector<float> Relighter::lutsFor(const RelightFrame& frame, const std::vector<float>& quantiles) const {
    const auto entries = static_cast<std::size_t>(m_bank.entries),
               samples = static_cast<std::size_t>(m_bank.prediction.quantiles);
    const float match = matchAt(frame.light, frame.view);
    std::vector<float> luts;
    for (std::size_t r = 0; r < m_regionTexels.size(); ++r)
        for (int c = 0; c < m_counted; ++c) {
            const LevelCounts counts = predictedCounts(frame, r, c);
            const float* q =
                &quantiles[(r * static_cast<std::size_t>(m_counted) + static_cast<std::size_t>(c)) * samples];
            std::vector<float> target(q, q + samples);
            if (match < 1) {
                const std::vector<float> own = quantileFunction(ownValues(counts), static_cast<int>(samples));
                for (std::size_t m = 0; m < samples; ++m) target[m] = match * target[m] + (1 - match) * own[m];
            }
            const Lut lut = matchToQuantiles(counts, target, static_cast<int>(entries));
            luts.insert(luts.end(), lut.values.begin(), lut.values.end());
        }
    return luts;
}

Image Relighter::apply(const RelightFrame& frame, bool dither) const {
    const float targetCode = dither ? m_bank.targetCode() : 0.f;
    if (!m_bank.makesLuts()) return applyLuts(m_bank.reference, m_bank.colour, frame.luts, m_bank.entries, targetCode);
    const LutBank::Prediction& blend = m_bank.prediction;
    const Image& first = m_bank.reference;  // its size, and its channels a grey bank gives out
    const ColourMode colour = m_bank.colour;
    const int outChannels = colour == ColourMode::Grey ? first.channels : 3;
    Image out(first.width, first.height, outChannels, m_bank.reference.bitDepth);
    const auto width = static_cast<std::uint32_t>(first.width);
    const auto entries = static_cast<std::size_t>(m_bank.entries);
    const float code = inputCode();
    for (std::size_t i = 0; i < out.pixelCount(); ++i) {
        const std::size_t region = blend.labels.empty() ? 0 : blend.labels[i];
        const auto x = static_cast<std::uint32_t>(i % width), y = static_cast<std::uint32_t>(i / width);
        auto map = [&](int c) {
            const float v = static_cast<float>(predictedCode(frame, i, c) + 1) * code;
            const float* lut =
                &frame.luts[(region * static_cast<std::size_t>(m_counted) + static_cast<std::size_t>(c)) * entries];
            if (!dither) return Lut::applyLut(lut, m_bank.entries, v);
            return lutOutput(Lut::applyLut(lut, m_bank.entries, lutInput(v, x, y, code, static_cast<std::uint32_t>(c))),
                             targetCode);
        };
        float* p = &out.samples[i * static_cast<std::size_t>(outChannels)];
        if (colour == ColourMode::Rgb) {
            for (int c = 0; c < 3; ++c) p[c] = map(c);
        } else if (outChannels == 1) {
            p[0] = map(0);
        } else {
            // The chroma: the blended references' (grey), the albedo's (lrgb) or the model's.
            m_predictor->colour(frame, i, p);
            setGrey(p, (p[0] + p[1] + p[2]) * (1.f / 3.f), map(0));
        }
    }
    return out;
}

Image Relighter::applyBlendingLuts(Direction light, Direction view, bool dither) const {
    const RelightFrame blended = frame(light, view);
    if (!m_bank.makesLuts() || blended.count == 1) return apply(blended, dither);
    // Each reference alone, matched to the same target, then the results blended.
    const BankLookup target = m_bank.lookup(light, view);
    Image out;
    for (int k = 0; k < blended.count; ++k) {
        RelightFrame alone = blended;
        alone.count = 1;
        alone.references = {blended.references[static_cast<std::size_t>(k)], 0, 0};
        alone.weights = {kWeightUnit, 0, 0};
        alone.luts = lutsFor(alone, target.values);
        const Image matched = apply(alone, dither);
        if (out.samples.empty()) {
            out = matched;
            for (float& v : out.samples) v = 0;
        }
        const float weight = static_cast<float>(blended.weights[static_cast<std::size_t>(k)]) / kWeightUnit;
        for (std::size_t s = 0; s < out.samples.size(); ++s) out.samples[s] += weight * matched.samples[s];
    }
    return out;
}

float matchRampRadius(const LutBank& bank) { return rampRadius(measuredDiskPoints(bank)); }

Image relight(const LutBank& bank, Direction light, Direction view, bool dither) {
    BTFLUT_CHECK(!bank.reference.samples.empty());
    const Relighter relighter(bank);
    return relighter.apply(relighter.frame(light, view), dither);
}

}  // namespace btflut
