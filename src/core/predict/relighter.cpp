#include "core/predict/relighter.h"

#include <algorithm>
#include <cmath>

namespace btflut {

Relighter::Relighter(const LutBank& bank) : m_bank(bank) {
    if (!bank.makesLuts()) return;
    const LutBank::Blend& blend = bank.blend;
    m_regionTexels.resize(static_cast<std::size_t>(blend.regions));
    for (std::size_t i = 0; i < blend.mask.inside.size(); ++i)
        if (blend.mask.inside[i])
            m_regionTexels[blend.labels.empty() ? 0 : blend.labels[i]].push_back(static_cast<std::uint32_t>(i));
    if (usesPtm()) {  // its grey on the scale of RGB8's grey codes
        BTFLUT_CHECK(!bank.ptm.empty());
        m_codes = 765;
        return;
    }
    BTFLUT_CHECK(!blend.references.empty());
    const Image& first = blend.references.front();
    BTFLUT_CHECK(first.bitDepth == 8);  // the blend's codes are 8-bit (bakeBank's blendForm)
    m_counted = bank.colour == ColourMode::Rgb ? 3 : 1;
    m_codes = 255 * (m_counted == 1 ? first.channels : 1);
    auto code = [](float v) { return static_cast<std::int32_t>(std::lround(v * 255.f)); };
    for (const Image& reference : blend.references) {
        std::vector<std::int32_t> codes(reference.pixelCount() * static_cast<std::size_t>(m_counted));
        for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
            const float* p = &reference.samples[i * static_cast<std::size_t>(reference.channels)];
            if (m_counted == 3 || reference.channels == 1) {
                for (int c = 0; c < m_counted; ++c) codes[i * m_counted + c] = code(p[c]);
            } else {  // the grey of RGB on its exact code scale: the sum of the channel codes
                codes[i] = code(p[0]) + code(p[1]) + code(p[2]);
            }
        }
        m_referenceCodes.push_back(std::move(codes));
    }
}

PtmFixed ptmFixed(const Ptm& ptm, Direction light) {
    const PtmWeights w = ptmWeights(ptm.scale, ptm.bias, light);
    // The most fraction bits (shift) that keep |offset| + 255 sum |weights| below 2^23.
    double bound = std::abs(double{w.offset});  // the largest |luminance| (bytes at most 255)
    for (float k : w.weights) bound += std::abs(double{k});
    int shift = 0;
    while (shift < 40 && bound * std::ldexp(1.0, shift + 1) < 0x1p23) ++shift;
    PtmFixed f;
    for (std::size_t k = 0; k < Ptm::kTerms; ++k)
        f.weights[k] = static_cast<std::int32_t>(std::lround(double{w.weights[k]} / 255 * std::ldexp(1.0, shift)));
    f.offset = static_cast<std::int32_t>(std::lround(double{w.offset} * std::ldexp(1.0, shift)));
    f.scale = static_cast<float>(std::ldexp(1.0, 12 - shift));  // to luminance * kWeightUnit (2^12)
    return f;
}

std::array<std::int64_t, 3> Relighter::ptmChannels(const PtmFixed& ptm, std::size_t texel) const {
    static_assert(kWeightUnit == 4096, "ptmFixed scales to 2^12");
    const std::uint8_t* a = &m_bank.ptm.coefficients[texel * Ptm::kTerms];
    std::int64_t sum = ptm.offset;
    for (std::size_t k = 0; k < Ptm::kTerms; ++k) sum += std::int64_t{a[k]} * ptm.weights[k];
    const auto luminance = static_cast<std::int64_t>(std::floor(static_cast<double>(sum) * ptm.scale));
    std::array<std::int64_t, 3> channels{};
    for (std::size_t c = 0; c < 3; ++c)
        channels[c] = std::clamp<std::int64_t>(std::int64_t{m_bank.ptm.albedo[texel * 3 + c]} * luminance, 0, 255 * kWeightUnit);
    return channels;
}

std::size_t Relighter::predictedCode(const RelightFrame& frame, std::size_t texel, int channel) const {
    // floor(sum / kWeightUnit + 1/2): exact in float too, the sum being an integer below 2^24.
    std::int64_t sum = 0;
    if (usesPtm()) {
        const std::array<std::int64_t, 3> c = ptmChannels(frame.ptm, texel);
        sum = c[0] + c[1] + c[2];
    } else {
        for (int k = 0; k < frame.count; ++k)
            sum += std::int64_t{frame.weights[static_cast<std::size_t>(k)]} *
                   m_referenceCodes[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])][texel * m_counted + channel];
    }
    return static_cast<std::size_t>(std::clamp<std::int64_t>((sum + kWeightUnit / 2) / kWeightUnit, 0, m_codes));
}

RelightFrame Relighter::frame(Direction light, Direction view, bool interpolate) const {
    RelightFrame frame;
    frame.light = light;
    frame.target = m_bank.lookup(light, view, interpolate);
    const BankLookup& target = frame.target;
    frame.provenance = target.provenance;
    frame.lightProvenance = target.lightProvenance;
    frame.viewProvenance = target.viewProvenance;
    if (!m_bank.makesLuts()) {
        frame.luts = target.values;
        return frame;
    }
    frame.count = 0;
    if (usesPtm()) {
        frame.ptm = ptmFixed(m_bank.ptm, light);
        frame.luts = lutsFor(frame, target.values);
        return frame;
    }
    // Barycentric weights in 1 / kWeightUnit; the largest takes the rounding so they sum to it.
    const Weights w = m_bank.blend.triangulation.weightsAt(toDisk(light));
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
    frame.luts = lutsFor(frame, target.values);
    return frame;
}

// Per region and channel: the blend's codes over the region's sample texels, matched to the
// region's target quantile function.
std::vector<float> Relighter::lutsFor(const RelightFrame& frame, const std::vector<float>& quantiles) const {
    const auto entries = static_cast<std::size_t>(m_bank.entries), samples = static_cast<std::size_t>(m_bank.blend.quantiles);
    std::vector<float> luts;
    for (std::size_t r = 0; r < m_regionTexels.size(); ++r)
        for (int c = 0; c < m_counted; ++c) {
            // Code q at value (q + 1) / (codes + 1): every code's cell lies inside [0, 1]
            // (code 0 of these counts stays empty).
            LevelCounts counts;
            counts.counts.assign(static_cast<std::size_t>(m_codes) + 2, 0);
            for (std::uint32_t texel : m_regionTexels[r]) ++counts.counts[predictedCode(frame, texel, c) + 1];
            const float* q = &quantiles[(r * static_cast<std::size_t>(m_counted) + static_cast<std::size_t>(c)) * samples];
            const Lut lut = matchToQuantiles(counts, std::span(q, samples), static_cast<int>(entries));
            luts.insert(luts.end(), lut.values.begin(), lut.values.end());
        }
    return luts;
}

Image Relighter::apply(const RelightFrame& frame, bool dither) const {
    const float targetCode = dither ? m_bank.targetCode() : 0.f;
    if (!m_bank.makesLuts()) return applyLuts(m_bank.reference, m_bank.colour, frame.luts, m_bank.entries, targetCode);
    const LutBank::Blend& blend = m_bank.blend;
    const Image& first = usesPtm() ? m_bank.reference : blend.references.front();
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
            const float* lut = &frame.luts[(region * static_cast<std::size_t>(m_counted) + static_cast<std::size_t>(c)) * entries];
            if (!dither) return Lut::applyLut(lut, m_bank.entries, v);
            return lutOutput(Lut::applyLut(lut, m_bank.entries, lutInput(v, x, y, code, static_cast<std::uint32_t>(c))), targetCode);
        };
        float* p = &out.samples[i * static_cast<std::size_t>(outChannels)];
        if (colour == ColourMode::Rgb) {
            for (int c = 0; c < 3; ++c) p[c] = map(c);
        } else if (outChannels == 1) {
            p[0] = map(0);
        } else {
            // The chroma: the blended references' (grey), the albedo's (lrgb) or the PTM's.
            if (usesPtm()) {
                const std::array<std::int64_t, 3> c = ptmChannels(frame.ptm, i);
                for (std::size_t k = 0; k < 3; ++k) p[k] = static_cast<float>(c[k]) / (255.f * kWeightUnit);
            } else if (colour == ColourMode::Lrgb) {
                std::copy_n(&blend.albedo.samples[i * 3], 3, p);
            } else {
                for (int c = 0; c < 3; ++c) {
                    p[c] = 0;
                    for (int k = 0; k < frame.count; ++k)
                        p[c] += static_cast<float>(frame.weights[static_cast<std::size_t>(k)]) / kWeightUnit *
                                blend.references[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])].samples[i * 3 + c];
                }
            }
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

Image relight(const LutBank& bank, Direction light, Direction view, bool dither) {
    BTFLUT_CHECK(!bank.reference.samples.empty());
    const Relighter relighter(bank);
    return relighter.apply(relighter.frame(light, view), dither);
}

}  // namespace btflut
