#include "core/relighter.h"

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
    if (usesPtm()) {
        // The PTM's coefficients decoded once; its grey on the scale of RGB8's grey codes.
        const Ptm& ptm = bank.ptm;
        BTFLUT_CHECK(!ptm.empty());
        m_codes = 765;
        m_ptmCoefficients.resize(ptm.coefficients.size());
        for (std::size_t i = 0; i < ptm.coefficients.size(); ++i) {
            const std::size_t k = i % Ptm::kTerms;
            m_ptmCoefficients[i] = (static_cast<float>(ptm.coefficients[i]) - ptm.bias[k]) * ptm.scale[k];
        }
        return;
    }
    BTFLUT_CHECK(!blend.references.empty());
    const Image& first = blend.references.front();
    m_counted = bank.colour == ColourMode::Rgb ? 3 : 1;
    m_codes = first.maxCode() * (m_counted == 1 ? first.channels : 1);
    const auto maxCode = static_cast<float>(first.maxCode());
    for (const Image& reference : blend.references) {
        std::vector<std::uint32_t> codes(reference.pixelCount() * static_cast<std::size_t>(m_counted));
        for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
            const float* p = &reference.samples[i * static_cast<std::size_t>(reference.channels)];
            if (m_counted == 3 || reference.channels == 1) {
                for (int c = 0; c < m_counted; ++c) codes[i * m_counted + c] = static_cast<std::uint32_t>(std::lround(p[c] * maxCode));
            } else {  // the grey of RGB on its exact code scale: the sum of the channel codes
                codes[i] = static_cast<std::uint32_t>(std::lround(p[0] * maxCode) + std::lround(p[1] * maxCode) +
                                                      std::lround(p[2] * maxCode));
            }
        }
        m_referenceCodes.push_back(std::move(codes));
    }
}

void Relighter::ptmColour(const std::array<double, Ptm::kTerms>& terms, std::size_t texel, float* rgb) const {
    double luminance = 0;
    for (int k = 0; k < Ptm::kTerms; ++k) luminance += m_ptmCoefficients[texel * Ptm::kTerms + static_cast<std::size_t>(k)] * terms[static_cast<std::size_t>(k)];
    for (int c = 0; c < 3; ++c)
        rgb[c] = static_cast<float>(std::clamp(m_bank.ptm.albedo[texel * 3 + static_cast<std::size_t>(c)] / 255.0 * luminance, 0.0, 1.0));
}

std::size_t Relighter::predictedCode(const RelightFrame& frame, const std::array<double, Ptm::kTerms>& terms,
                                     std::size_t texel, int channel) const {
    if (usesPtm()) {
        float rgb[3];
        ptmColour(terms, texel, rgb);
        return static_cast<std::size_t>(std::lround((rgb[0] + rgb[1] + rgb[2]) * 255.f));
    }
    return static_cast<std::size_t>(std::clamp(std::lround(blendCode(frame, texel, channel)), 0L, static_cast<long>(m_codes)));
}

double Relighter::blendCode(const RelightFrame& frame, std::size_t texel, int channel) const {
    double code = 0;
    for (int k = 0; k < frame.count; ++k)
        code += frame.weights[static_cast<std::size_t>(k)] *
                m_referenceCodes[static_cast<std::size_t>(frame.references[static_cast<std::size_t>(k)])][texel * m_counted + channel];
    return code;
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
        frame.luts = lutsFor(frame, target.values);
        return frame;
    }
    const Weights w = m_bank.blend.triangulation.weightsAt(toDisk(light));
    for (int k = 0; k < w.count; ++k) {
        if (w.weight[static_cast<std::size_t>(k)] <= 0) continue;
        frame.references[static_cast<std::size_t>(frame.count)] = w.index[static_cast<std::size_t>(k)];
        frame.weights[static_cast<std::size_t>(frame.count)] = static_cast<float>(w.weight[static_cast<std::size_t>(k)]);
        ++frame.count;
    }
    frame.luts = lutsFor(frame, target.values);
    return frame;
}

// Per region and channel: the blend's codes over the region's sample texels, matched to the
// region's target quantile function.
std::vector<float> Relighter::lutsFor(const RelightFrame& frame, const std::vector<float>& quantiles) const {
    const auto entries = static_cast<std::size_t>(m_bank.entries), samples = static_cast<std::size_t>(m_bank.blend.quantiles);
    const std::array<double, Ptm::kTerms> terms = Ptm::terms(frame.light);
    std::vector<float> luts;
    for (std::size_t r = 0; r < m_regionTexels.size(); ++r)
        for (int c = 0; c < m_counted; ++c) {
            // Code q at value (q + 1) / (codes + 1): every code's cell lies inside [0, 1]
            // (code 0 of these counts stays empty).
            LevelCounts counts;
            counts.counts.assign(static_cast<std::size_t>(m_codes) + 2, 0);
            for (std::uint32_t texel : m_regionTexels[r]) ++counts.counts[predictedCode(frame, terms, texel, c) + 1];
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
    const std::array<double, Ptm::kTerms> terms = Ptm::terms(frame.light);
    const auto width = static_cast<std::uint32_t>(first.width);
    const auto entries = static_cast<std::size_t>(m_bank.entries);
    const float code = inputCode();
    for (std::size_t i = 0; i < out.pixelCount(); ++i) {
        const std::size_t region = blend.labels.empty() ? 0 : blend.labels[i];
        const auto x = static_cast<std::uint32_t>(i % width), y = static_cast<std::uint32_t>(i / width);
        float predicted[3];  // the PTM predictor's colour
        if (usesPtm()) ptmColour(terms, i, predicted);
        auto map = [&](int c) {
            const float v = static_cast<float>(predictedCode(frame, terms, i, c) + 1) * code;
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
                std::copy_n(predicted, 3, p);
            } else if (colour == ColourMode::Lrgb) {
                std::copy_n(&blend.albedo.samples[i * 3], 3, p);
            } else {
                for (int c = 0; c < 3; ++c) {
                    p[c] = 0;
                    for (int k = 0; k < frame.count; ++k)
                        p[c] += frame.weights[static_cast<std::size_t>(k)] *
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
        alone.weights = {1, 0, 0};
        alone.luts = lutsFor(alone, target.values);
        const Image matched = apply(alone, dither);
        if (out.samples.empty()) {
            out = matched;
            for (float& v : out.samples) v = 0;
        }
        for (std::size_t s = 0; s < out.samples.size(); ++s) out.samples[s] += blended.weights[static_cast<std::size_t>(k)] * matched.samples[s];
    }
    return out;
}

Image relight(const LutBank& bank, Direction light, Direction view, bool dither) {
    BTFLUT_CHECK(!bank.reference.samples.empty());
    const Relighter relighter(bank);
    return relighter.apply(relighter.frame(light, view), dither);
}

}  // namespace btflut
