#pragma once
// Polynomial Texture Maps (Malzbender, Gelb and Wolters 2001) in the LRGB form RTI viewers
// draw: per texel, six luminance coefficients biquadratic in the projected light direction
// (u, v) = (x, y) of the unit light vector in the sample frame, times an RGB albedo:
//
//   L(u, v) = a0 u^2 + a1 v^2 + a2 u v + a3 u + a4 v + a5,        rgb = albedo * L.
//
// Coefficients are bytes with one scale and bias per coefficient, as in the .ptm format:
// a_k = (byte - bias_k) * scale_k. btflut fits PTMs from the same images as its LUT banks, as
// the baseline the LUT renderer is measured against (renderer modes `ptm` and `lut`).
//
//   PtmFitter fitter(width, height);
//   fitter.add(image, light);                    // every image of one view, any order, any thread
//   Result<Ptm> ptm = fitter.finish("rock");    // least squares per texel, then quantised
//   Image relit = ptm->render(light);            // CPU reference of the shader

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/result.h"

namespace btflut {

struct Ptm {
    static constexpr int kTerms = 6;

    int width = 0, height = 0;
    std::array<float, kTerms> scale{}, bias{};
    std::vector<std::uint8_t> coefficients;  ///< kTerms bytes per texel, rows top first
    std::vector<std::uint8_t> albedo;        ///< RGB bytes per texel

    bool empty() const { return coefficients.empty(); }
    std::size_t texels() const { return static_cast<std::size_t>(width) * height; }

    /// The three RGB planes textures and files hold, as bytes per texel: coefficients 0-2,
    /// coefficients 3-5, and the albedo (plane 0, 1 or 2).
    std::vector<std::uint8_t> plane(int index) const;

    /// (u^2, v^2, u v, u, v, 1) for a light direction.
    static std::array<double, kTerms> terms(Direction light);
    /// The relit image (RGB, 8-bit precision), clamped to [0, 1].
    Image render(Direction light) const;
};

/// A PTM's six per-coefficient weights and offset for a light, its terms with each
/// coefficient's scale and bias folded in (as RTI viewers draw, once per light):
/// luminance = sum_k byte_k / 255 * weights[k] + offset.
struct PtmWeights {
    std::array<float, Ptm::kTerms> weights{};
    float offset = 0;
};
PtmWeights ptmWeights(const std::array<float, Ptm::kTerms>& scale, const std::array<float, Ptm::kTerms>& bias,
                      Direction light);

/// Accumulates the normal equations of the per-texel least-squares fit while images stream
/// past; `add` may be called from several threads.
class PtmFitter {
public:
    PtmFitter(int width, int height);
    void add(const Image& image, Direction light);
    /// Needs at least six light directions that determine the six terms; `what` names the
    /// dataset in errors.
    Result<Ptm> finish(const std::string& what) const;

private:
    int m_width, m_height;
    mutable std::mutex m_mutex;
    std::size_t m_images = 0;
    std::array<double, Ptm::kTerms * Ptm::kTerms> m_normal{};  ///< sum of t t^T (same for all texels)
    std::vector<float> m_moments;                              ///< per texel: sum of t * grey (kTerms)
    std::vector<float> m_colour;                               ///< per texel: sum of R, G, B
};

}  // namespace btflut
