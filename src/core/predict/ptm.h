#pragma once
// The bank's baseline PTM (Malzbender, Gelb and Wolters 2001), the light model of basis ptm
// (light_model.h) in the LRGB form RTI viewers draw: per texel, six luminance coefficients
// biquadratic in the projected light direction (u, v) = (x, y) of the unit light vector in
// the sample frame, times an RGB albedo:
//
//   L(u, v) = a0 u^2 + a1 v^2 + a2 u v + a3 u + a4 v + a5,        rgb = albedo * L.
//
// Coefficients are bytes with one scale and bias per coefficient, as in the .ptm format
// (ptm_file.h). `bake --ptm` fits it from the images of the reference's view as they stream
// past (each read once), as the baseline the LUT renderer is measured against (renderer modes
// `ptm` and `lut`); `--predictor ptm` fits the same basis by fitLightModel, as a predictor.
//
//   PtmFitter fitter(width, height);
//   fitter.add(image, light);                         // every image of one view, any order, any thread
//   Result<LightModel> ptm = fitter.finish("rock");   // least squares per texel, then quantised
//   Image relit = ptm->render(light);                 // CPU reference of the shader

#include <array>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/io/byte_stream.h"
#include "core/predict/chunk_planes.h"
#include "core/predict/light_model.h"
#include "core/result.h"

namespace btflut {

/// A PTM's light model before its planes are filled: basis ptm, its six 8-bit planes, each of
/// scale 1 and bias 0 (the fit, the .ptm file and the bank's chunk set their own).
LightModel ptmShell(int width, int height);

/// A PTM's six per-coefficient weights and offset for a light, its terms with each
/// coefficient's scale and bias folded in (as RTI viewers draw, once per light):
/// luminance = sum_k byte_k / 255 * weights[k] + offset.
struct PtmWeights {
    std::array<float, kPtmTerms> weights{};
    float offset = 0;
};
PtmWeights ptmWeights(std::span<const float> scale, std::span<const float> bias, Direction light);

/// Accumulates the normal equations of the per-texel least-squares fit while images stream
/// past; `add` may be called from several threads.
class PtmFitter {
public:
    PtmFitter(int width, int height);
    void add(const Image& image, Direction light);
    /// A light model of basis ptm (LRGB: six 8-bit planes and the albedo). Needs at least six
    /// light directions that determine the six terms; `what` names the dataset in errors.
    Result<LightModel> finish(const std::string& what) const;

private:
    int m_width, m_height;
    mutable std::mutex m_mutex;
    std::size_t m_images = 0;
    std::array<double, kPtmTerms * kPtmTerms> m_normal{};  ///< sum of t t^T (same for all texels)
    std::vector<float> m_moments;                          ///< per texel: sum of t * grey (kPtmTerms)
    std::vector<float> m_colour;                           ///< per texel: sum of R, G, B
};

/// A bank's PTM as its chunk of a .btflut file (PTMC, docs/btflut-format.md): width, height
/// (u32), scale[6], bias[6] (f32), then three PNGs, each preceded by its byte length (u32):
/// coefficients 0-2, coefficients 3-5, albedo (RGB8).
Bytes encodePtmChunk(const LightModel& ptm);
/// The chunk read back: its size must be the reference's (`source`: already checked against
/// the pixel limit) before anything is allocated.
Result<LightModel> decodePtmChunk(ByteReader& in, const ChunkSource& source);

}  // namespace btflut
