#include "core/predict/ptm.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace btflut {

PtmWeights ptmWeights(std::span<const float> scale, std::span<const float> bias, Direction light) {
    constexpr auto K = static_cast<std::size_t>(kPtmTerms);
    BTFLUT_CHECK(scale.size() == K && bias.size() == K);
    const std::vector<double> t = basisTerms(LightBasis::Ptm, 0, light);
    PtmWeights w;
    double offset = 0;
    for (std::size_t k = 0; k < K; ++k) {
        w.weights[k] = static_cast<float>(255.0 * scale[k] * t[k]);
        offset -= double{bias[k]} * scale[k] * t[k];
    }
    w.offset = static_cast<float>(offset);
    return w;
}

PtmFitter::PtmFitter(int width, int height)
    : m_width(width),
      m_height(height),
      m_moments(static_cast<std::size_t>(width) * height * kPtmTerms),
      m_colour(static_cast<std::size_t>(width) * height * 3) {}

void PtmFitter::add(const Image& image, Direction light) {
    const std::vector<double> t = basisTerms(LightBasis::Ptm, 0, light);
    std::array<float, kPtmTerms> tf;
    for (int k = 0; k < kPtmTerms; ++k) tf[k] = static_cast<float>(t[k]);
    std::lock_guard lock(m_mutex);
    ++m_images;
    for (int a = 0; a < kPtmTerms; ++a)
        for (int b = 0; b < kPtmTerms; ++b) m_normal[a * kPtmTerms + b] += t[a] * t[b];
    for (std::size_t i = 0; i < image.pixelCount(); ++i) {
        const float grey = image.grey(i);
        for (int k = 0; k < kPtmTerms; ++k) m_moments[i * kPtmTerms + k] += tf[k] * grey;
        for (int c = 0; c < 3; ++c)
            m_colour[i * 3 + c] += image.samples[i * image.channels + (image.channels == 3 ? c : 0)];
    }
}

LightModel ptmShell(int width, int height) {
    LightModel ptm;
    ptm.basis = LightBasis::Ptm;
    ptm.width = width;
    ptm.height = height;
    ptm.planes = ptm.wide = kPtmTerms;
    ptm.scale.assign(kPtmTerms, 1.f);
    ptm.bias.assign(kPtmTerms, 0.f);
    return ptm;
}

Result<LightModel> PtmFitter::finish(const std::string& what) const {
    std::lock_guard lock(m_mutex);
    const Eigen::Matrix<double, kPtmTerms, kPtmTerms> normal(m_normal.data());
    Eigen::JacobiSVD<Eigen::Matrix<double, kPtmTerms, kPtmTerms>> svd(normal);
    const double condition = svd.singularValues()(0) / svd.singularValues()(kPtmTerms - 1);
    if (m_images < kPtmTerms || !std::isfinite(condition) || condition > 1e8)
        return Error{what +
                     ": a PTM needs at least six light directions spread enough to fit u^2, v^2, uv, "
                     "u, v and 1; these " +
                     std::to_string(m_images) + " do not determine them"};
    const Eigen::Matrix<double, kPtmTerms, kPtmTerms> inverse = normal.inverse();

    // Least squares on the grey value; the albedo carries the texel's colour, scaled so its
    // largest channel is 1 and the luminance scaled to match.
    const std::size_t texels = static_cast<std::size_t>(m_width) * m_height;
    std::vector<double> fitted(texels * kPtmTerms);
    LightModel ptm = ptmShell(m_width, m_height);
    ptm.albedo.resize(texels * 3);
    for (std::size_t i = 0; i < texels; ++i) {
        const float* colour = &m_colour[i * 3];
        const double grey = (double{colour[0]} + colour[1] + colour[2]) / 3;
        const double top = std::max({colour[0], colour[1], colour[2]});
        const double luminanceScale = grey > 0 ? top / grey : 1.0;
        for (int c = 0; c < 3; ++c)
            ptm.albedo[i * 3 + c] = static_cast<std::uint8_t>(top > 0 ? std::lround(255 * colour[c] / top) : 255);
        const Eigen::Map<const Eigen::Matrix<float, kPtmTerms, 1>> moments(&m_moments[i * kPtmTerms]);
        Eigen::Map<Eigen::Matrix<double, kPtmTerms, 1>> a(&fitted[i * kPtmTerms]);
        a = inverse * moments.cast<double>() * luminanceScale;
    }
    for (int k = 0; k < kPtmTerms; ++k) {
        double low = fitted[k], high = fitted[k];
        for (std::size_t i = 0; i < texels; ++i) {
            low = std::min(low, fitted[i * kPtmTerms + k]);
            high = std::max(high, fitted[i * kPtmTerms + k]);
        }
        ptm.scale[k] = static_cast<float>(high > low ? (high - low) / 255 : 1.0);
        ptm.bias[k] = static_cast<float>(-low / ptm.scale[k]);
    }
    ptm.coefficients.resize(texels * kPtmTerms);
    for (std::size_t i = 0; i < texels * kPtmTerms; ++i) {
        const int k = static_cast<int>(i % kPtmTerms);
        ptm.coefficients[i] =
            static_cast<std::uint8_t>(std::clamp<long>(std::lround(fitted[i] / ptm.scale[k] + ptm.bias[k]), 0, 255));
    }
    return ptm;
}

Bytes encodePtmChunk(const LightModel& ptm) {
    ByteWriter w;
    w.put(static_cast<std::uint32_t>(ptm.width));
    w.put(static_cast<std::uint32_t>(ptm.height));
    for (float v : ptm.scale) w.put(v);
    for (float v : ptm.bias) w.put(v);
    for (const Image& image : lightModelImages(ptm)) putPng(w, image, 8);  // coefficients 0-2, 3-5, the albedo
    return std::move(w.bytes());
}

Result<LightModel> decodePtmChunk(ByteReader& in, const ChunkSource& source) {
    auto fail = [&](const std::string& what) { return source.fail(what); };
    const auto w = in.get<std::uint32_t>(), h = in.get<std::uint32_t>();
    LightModel ptm = ptmShell(source.width, source.height);
    for (std::vector<float>* values : {&ptm.scale, &ptm.bias})
        for (float& v : *values) v = in.get<float>();
    if (!in.ok()) return fail("invalid header");
    if (w != static_cast<std::uint32_t>(source.width) || h != static_cast<std::uint32_t>(source.height))
        return Error{source.name + ": the PTM (" + std::to_string(w) + "x" + std::to_string(h) +
                     ") does not match the reference image's size"};
    for (std::size_t k = 0; k < ptm.scale.size(); ++k)
        if (!std::isfinite(ptm.scale[k]) || !std::isfinite(ptm.bias[k]) || ptm.scale[k] <= 0)
            return fail("invalid scale or bias");
    ptm.albedo.resize(ptm.texels() * 3);
    if (Status s = readModelPlanes(in, source, source.name + " (PTM ", "coefficients ", ptm); !s)
        return Error{s.error()};
    if (in.remaining() != 0) return fail("has the wrong size");
    return ptm;
}

}  // namespace btflut
