#pragma once
// Linear light models: the per-texel predictors of RTI tools as one form. A texel stores P
// coefficient planes (bytes, plane p's value v_p = (byte_p - bias_p) scale_p) and, in the
// LRGB layout, an RGB albedo; a light L gives each plane and output channel a weight
// w_pc(L) and each channel an offset o_c(L). The prediction of channel c is
//
//   pred_c = a_c (o_c(L) + sum_p v_p w_pc(L)),   clamped to [0, 1],
//
// a_c the albedo (byte / 255) in the LRGB layout, 1 otherwise. The bases differ only in
// w(L):
//   ptm  Malzbender's biquadratic (u^2, v^2, uv, u, v, 1) in the light's (x, y); LRGB.
//   hsh  hemispherical harmonics (Gautron et al. 2004) of order 2 (4 terms) or 3 (9); LRGB.
//   rbf  a PCA basis of the training images (mean and P principal components over every
//        light and channel): w and o at L are the components' values at the training
//        lights, blended by normalised Gaussian weights of the distance to L.
//   bln  the same PCA basis resampled on a G x G grid over the equal-area light disk
//        (regularised least squares), read bilinearly.
// The texture-space GL pass evaluates the same sums in the same integers
// (LightModelFixed; shaders/btflut.glsl's btflutModelFrame and lut_common.glsl), so CPU and GPU
// predictions agree to the code.
//
//   Result<LightModel> m = fitLightModel(images, lights, mask, {.basis = LightBasis::Rbf, .planes = 9});
//   Image predicted = m->render(light);                 // float, the CPU reference
//   LightModelFixed f = lightModelFixed(*m, light);      // per light change: integer weights

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/predict/gpu_constants.h"
#include "core/result.h"

namespace btflut {

/// Predictions are exact integer arithmetic, so that the CPU and a GPU (whose float sums of
/// integers below 2^24 are exact, fused or not) get the same codes: reference weights are
/// integers summing to kWeightUnit, applied to the references' 8-bit codes, and a light
/// model's channels are scaled by it (LightModelFixed).
constexpr int kWeightUnit = BTFLUT_WEIGHT_UNIT;

/// The PTM's terms (u^2, v^2, u v, u, v, 1): ptm.h fits a bank's baseline PTM.
constexpr int kPtmTerms = 6;

enum class LightBasis : std::uint32_t {
    Ptm = BTFLUT_BASIS_PTM,
    Hsh = BTFLUT_BASIS_HSH,
    Rbf = BTFLUT_BASIS_RBF,
    Bilinear = BTFLUT_BASIS_BLN
};

const char* lightBasisName(LightBasis basis);
Result<LightBasis> parseLightBasis(const std::string& name);

struct LightModel {
    static constexpr int kMaxPlanes = BTFLUT_MAX_PLANES;

    LightBasis basis = LightBasis::Ptm;
    int width = 0, height = 0;
    int planes = 0;  ///< P, 1..kMaxPlanes
    /// The leading planes stored with 8 bits (codes 0..255); the others, the components of
    /// least variance, with 4 bits (codes 0..15, two to a byte in files and textures).
    int wide = 0;
    int channels = 1;                        ///< output channels: 1 (grey) or 3
    int order = 0;                           ///< hsh: 2 or 3
    std::vector<float> scale, bias;          ///< per plane: v_p = (byte_p - bias_p) * scale_p, scale > 0
    std::vector<std::uint8_t> coefficients;  ///< P codes per texel (one byte each in memory), rows top first
    std::vector<std::uint8_t> albedo;        ///< LRGB layout: RGB bytes per texel; empty otherwise

    /// rbf: the training lights and, per light, (1 + P) x channels values (the offset, then
    /// each plane's weight); sigma the Gaussian's width (unit-vector distance).
    std::vector<Direction> lights;
    float sigma = 0;
    /// bln: grid nodes per side G and, per node (j * G + i, disk point as LutBank::gridPoint),
    /// (1 + P) x channels values.
    int grid = 0;
    std::vector<float> table;  ///< rbf: per light; bln: per grid node

    bool empty() const { return coefficients.empty(); }
    std::size_t texels() const { return static_cast<std::size_t>(width) * height; }
    /// Bytes per texel the model stores: its planes (two 4-bit planes to a byte) and the albedo.
    int bytesPerTexel() const { return wide + (planes - wide + 1) / 2 + (albedo.empty() ? 0 : 3); }
    /// Multiply-adds a texel: each plane's weight per channel, and the albedo's product.
    std::size_t multiplyAdds() const { return static_cast<std::size_t>(planes * channels) + (albedo.empty() ? 0 : 3); }
    /// The largest code of plane p: 255 or 15.
    int maxCode(int p) const { return p < wide ? 255 : 15; }
    /// The basis's own terms count (ptm 6, hsh 4 or 9); 0 for the PCA bases.
    static int termCount(LightBasis basis, int order);

    /// w (planes x channels, plane-major) and o (channels) at a light.
    struct Weights {
        std::vector<float> weight;  ///< w[p * channels + c]
        std::array<float, 3> offset{};
    };
    Weights weightsAt(Direction light) const;

    /// The prediction (float, clamped to [0, 1]): grey when channels is 1, else RGB.
    Image render(Direction light) const;
};

/// The six PTM terms (u^2, v^2, u v, u, v, 1 of the light's x and y) or the 4 / 9 HSH terms of a light.
std::vector<double> basisTerms(LightBasis basis, int order, Direction light);

/// The per-light integers both the CPU and the shader evaluate (as PtmFixed, for every
/// basis): per channel S_c = offset_c + sum_p byte_p weights[p][c], exact below 2^23, and
/// L_c = floor(S_c * scale) = the channel's value before the albedo, times kWeightUnit; a
/// channel is clamp(a_c L_c, 0, 255 kWeightUnit) with a_c the albedo byte (255 without).
struct LightModelFixed {
    std::vector<std::int32_t> weights;  ///< [p * channels + c]
    std::array<std::int32_t, 3> offset{};
    float scale = 1;  ///< a power of two
};
LightModelFixed lightModelFixed(const LightModel& model, Direction light);

/// A texel's channels times 255 * kWeightUnit, clamped: the
/// fixed-point prediction, channels 1 or 3 (grey models give one).
std::array<std::int64_t, 3> predictFixed(const LightModel& model, const LightModelFixed& fixed, std::size_t texel);

/// The model's planes as RGB8 images, as files and engines hold them: the 8-bit planes three
/// to an image (planes 3k, 3k + 1, 3k + 2 in R, G, B; missing ones 0), then the 4-bit planes
/// six to an image (two to a channel, the first in the high nibble), then the albedo if any.
std::vector<Image> lightModelImages(const LightModel& model);

struct LightModelOptions {
    LightBasis basis = LightBasis::Rbf;
    int order = 3;   ///< hsh
    int planes = 9;  ///< rbf, bln: principal components kept (8-bit); with `packed`, bytes per texel
    /// rbf, bln: as many components as `planes` bytes hold, the leading ones 8-bit, the rest
    /// 4-bit, split where the training images are reconstructed best.
    bool packed = false;
    int grid = 8;        ///< bln: grid nodes per side over the light disk
    bool colour = true;  ///< rbf, bln: predict RGB (the images' colour); else grey
    int threads = 0;
};

/// A model from its command-line name: ptm; hsh (order 2), hsh2, hsh3; rbf and bln (9
/// planes), rbfN and blnN (N 8-bit planes), rbfNc and blnNc (N bytes of packed planes);
/// nothing when the name names no basis, an error for a number out of range.
std::optional<Result<LightModelOptions>> lightModelNamed(const std::string& name);

/// The model's name as the command line gives it: ptm, hsh2, hsh3, rbfN, blnN, rbfNc, blnNc.
std::string lightModelName(const LightModel& model);

/// Fits a model to images of one view under `lights` (same size; RGB or grey). ptm and hsh:
/// least squares per texel on the grey value, ridge-regularised where the lights leave a term
/// undetermined (the albedo is the texel's mean colour); refuses lights that determine too
/// little (`what` names the dataset). rbf, bln: PCA over the sample texels of `mask`.
Result<LightModel> fitLightModel(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                 const Mask& mask, const LightModelOptions& options, const std::string& what);

}  // namespace btflut
