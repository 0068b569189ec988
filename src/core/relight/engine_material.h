#pragma once
// A bank as an engine draws it, per fragment, with shaders/btflut.glsl: what `btflut export
// -o DIR/` writes (docs/engines.md) and what the viewer's sphere and cylinder upload, so both
// run the same shader on the same textures.
//
//   luts     every bank: a LUT per grid node of the light disk as one 3D texture of 16-bit
//            texels, entries x G x (G x blocks); a block is a view layer (banks of LUTs) or a
//            view layer's region, layer * regions + region (banks with a predictor: their
//            match LUTs, LutBank::matchGridLuts; several layers for a predictor of views).
//   planes   the predictor's (Predictor::planes, the packing btflut's own renderer uploads
//            too): a light model's (ptm, hsh, rbf, bln) as 8-bit codes four to an RGBA image
//            (4-bit planes as codes 17 n, their scale and bias adjusted: the same values),
//            per plane value = (code - bias) scale; a learned model's codes likewise; or the
//            references, one to an image (grey ones in every channel); then the albedo. The
//            weights: ptm and hsh in closed form (btflut.glsl), rbf, bln and references from
//            the weight grid; a learned model's decoder is the weight texture (one layer, a
//            square of texels: LearnedModel::gpuNetwork).
// The weight grid: S x S nodes over the equal-area light disk (node (i, j) at x = -1 + 2 i /
// (S - 1), y likewise), per node `weights` floats, four to a layer: [layer][j][i][4].
// Model rows hold the offsets, then each plane's channel weights ((1 + P) x channels, as
// LightModel::table); references rows one weight per reference.
//
//   Result<EngineMaterial> m = engineMaterial(bank, "m.btflut");

#include <cstdint>
#include <string>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/result.h"

namespace btflut {

/// What its predictor gives an engine (EngineParts: the basis, the weight grid, a learned
/// decoder's shaders; defaults for a bank of LUTs), and the bank's LUT grid and textures.
struct EngineMaterial : EngineParts {
    PredictorKind kind = PredictorKind::Luts;
    ColourMode colour = ColourMode::Grey;

    // The LUT grid (every kind).
    int entries = 0, gridSize = 0, blocks = 1, lutChannels = 1;
    std::vector<std::uint16_t> lutTexels;  ///< [block][j][i][entry][channel]
    float inputCode = 0;                   ///< one code of the LUTs' input
    float outputCode = 0;                  ///< one code of the values they map to
    int outputChannels = 1;                ///< of the relit image: 1 (grey) or 3

    // Luts: the reference, relit by the LUTs directly.
    Image reference;

    // Model, References and Learned: the predictor's planes (Predictor::planes).
    std::vector<float> scale, bias;  ///< Model, per plane, on the exported codes
    std::vector<Image> images;       ///< RGBA8: the planes four to an image, or one reference each
    Image albedo;                    ///< RGB8, empty when none
    int codes = 255;                 ///< codes of a prediction: 255, or 765 (the grey of RGB8)
    Image labels;                    ///< 8-bit region per texel, empty with one region
    int regions = 1;

    int weightLayers() const { return (weights + 3) / 4; }
    /// btflut.glsl's BtflutPredictor.kind (BTFLUT_KIND_...); 0 for Luts.
    int predictorKind() const { return static_cast<int>(kind); }
};

/// What an engine needs to draw `bank` (its first view layer's match grid for predictors,
/// made here for files older than it). Refuses banks without a reference; `name` names the
/// bank in the error.
Result<EngineMaterial> engineMaterial(const LutBank& bank, const std::string& name);

/// Whether a GPU can draw the bank: a learned model whose networks exceed the shader's arrays
/// (LearnedModel::fitsGpu; `bake` trains none) is relit on the CPU only. The error names no file.
Status drawnOnGpu(const LutBank& bank);

}  // namespace btflut
