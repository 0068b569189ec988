#include "core/predict/ptm.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace btflut {

std::array<double, Ptm::kTerms> Ptm::terms(Direction light) {
    const Vec3 l = toVector(light);
    return {l.x * l.x, l.y * l.y, l.x * l.y, l.x, l.y, 1.0};
}

std::vector<std::uint8_t> Ptm::plane(int index) const {
    if (index == 2) return albedo;
    std::vector<std::uint8_t> out(texels() * 3);
    for (std::size_t i = 0; i < texels(); ++i)
        std::copy_n(&coefficients[i * kTerms + 3 * static_cast<std::size_t>(index)], 3, &out[i * 3]);
    return out;
}

Image Ptm::render(Direction light) const {
    const std::array<double, kTerms> t = terms(light);
    Image out(width, height, 3);
    for (std::size_t i = 0; i < texels(); ++i) {
        double luminance = 0;
        for (int k = 0; k < kTerms; ++k)
            luminance += (coefficients[i * kTerms + k] - double{bias[k]}) * scale[k] * t[k];
        for (int c = 0; c < 3; ++c)
            out.samples[i * 3 + c] = static_cast<float>(std::clamp(albedo[i * 3 + c] / 255.0 * luminance, 0.0, 1.0));
    }
    return out;
}

PtmWeights ptmWeights(const std::array<float, Ptm::kTerms>& scale, const std::array<float, Ptm::kTerms>& bias,
                      Direction light) {
    const std::array<double, Ptm::kTerms> t = Ptm::terms(light);
    PtmWeights w;
    double offset = 0;
    for (std::size_t k = 0; k < Ptm::kTerms; ++k) {
        w.weights[k] = static_cast<float>(255.0 * scale[k] * t[k]);
        offset -= double{bias[k]} * scale[k] * t[k];
    }
    w.offset = static_cast<float>(offset);
    return w;
}

PtmFitter::PtmFitter(int width, int height)
    : m_width(width),
      m_height(height),
      m_moments(static_cast<std::size_t>(width) * height * Ptm::kTerms),
      m_colour(static_cast<std::size_t>(width) * height * 3) {}

void PtmFitter::add(const Image& image, Direction light) {
    const std::array<double, Ptm::kTerms> t = Ptm::terms(light);
    std::array<float, Ptm::kTerms> tf;
    for (int k = 0; k < Ptm::kTerms; ++k) tf[k] = static_cast<float>(t[k]);
    std::lock_guard lock(m_mutex);
    ++m_images;
    for (int a = 0; a < Ptm::kTerms; ++a)
        for (int b = 0; b < Ptm::kTerms; ++b) m_normal[a * Ptm::kTerms + b] += t[a] * t[b];
    for (std::size_t i = 0; i < image.pixelCount(); ++i) {
        const float grey = image.grey(i);
        for (int k = 0; k < Ptm::kTerms; ++k) m_moments[i * Ptm::kTerms + k] += tf[k] * grey;
        for (int c = 0; c < 3; ++c)
            m_colour[i * 3 + c] += image.samples[i * image.channels + (image.channels == 3 ? c : 0)];
    }
}

Result<Ptm> PtmFitter::finish(const std::string& what) const {
    std::lock_guard lock(m_mutex);
    const Eigen::Matrix<double, Ptm::kTerms, Ptm::kTerms> normal(m_normal.data());
    Eigen::JacobiSVD<Eigen::Matrix<double, Ptm::kTerms, Ptm::kTerms>> svd(normal);
    const double condition = svd.singularValues()(0) / svd.singularValues()(Ptm::kTerms - 1);
    if (m_images < Ptm::kTerms || !std::isfinite(condition) || condition > 1e8)
        return Error{what +
                     ": a PTM needs at least six light directions spread enough to fit u^2, v^2, uv, "
                     "u, v and 1; these " +
                     std::to_string(m_images) + " do not determine them"};
    const Eigen::Matrix<double, Ptm::kTerms, Ptm::kTerms> inverse = normal.inverse();

    // Least squares on the grey value; the albedo carries the texel's colour, scaled so its
    // largest channel is 1 and the luminance scaled to match.
    const std::size_t texels = static_cast<std::size_t>(m_width) * m_height;
    std::vector<double> fitted(texels * Ptm::kTerms);
    Ptm ptm;
    ptm.width = m_width;
    ptm.height = m_height;
    ptm.albedo.resize(texels * 3);
    for (std::size_t i = 0; i < texels; ++i) {
        const float* colour = &m_colour[i * 3];
        const double grey = (double{colour[0]} + colour[1] + colour[2]) / 3;
        const double top = std::max({colour[0], colour[1], colour[2]});
        const double luminanceScale = grey > 0 ? top / grey : 1.0;
        for (int c = 0; c < 3; ++c)
            ptm.albedo[i * 3 + c] = static_cast<std::uint8_t>(top > 0 ? std::lround(255 * colour[c] / top) : 255);
        const Eigen::Map<const Eigen::Matrix<float, Ptm::kTerms, 1>> moments(&m_moments[i * Ptm::kTerms]);
        Eigen::Map<Eigen::Matrix<double, Ptm::kTerms, 1>> a(&fitted[i * Ptm::kTerms]);
        a = inverse * moments.cast<double>() * luminanceScale;
    }
    for (int k = 0; k < Ptm::kTerms; ++k) {
        double low = fitted[k], high = fitted[k];
        for (std::size_t i = 0; i < texels; ++i) {
            low = std::min(low, fitted[i * Ptm::kTerms + k]);
            high = std::max(high, fitted[i * Ptm::kTerms + k]);
        }
        ptm.scale[k] = static_cast<float>(high > low ? (high - low) / 255 : 1.0);
        ptm.bias[k] = static_cast<float>(-low / ptm.scale[k]);
    }
    ptm.coefficients.resize(texels * Ptm::kTerms);
    for (std::size_t i = 0; i < texels * Ptm::kTerms; ++i) {
        const int k = static_cast<int>(i % Ptm::kTerms);
        ptm.coefficients[i] =
            static_cast<std::uint8_t>(std::clamp<long>(std::lround(fitted[i] / ptm.scale[k] + ptm.bias[k]), 0, 255));
    }
    return ptm;
}

}  // namespace btflut
