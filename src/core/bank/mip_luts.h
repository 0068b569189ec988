#pragma once
// LUTs for a texture's mipmap levels. A level-m texel is the mean of a block of the base
// level's texels; a LUT is not linear, so LUT(mean) is not the block's mean of LUT values: a
// far quad's brightness and contrast would drift with distance (a grazing light's LUT that
// sends the darker grey levels to black turns averaged mid-greys into the wrong value).
// Where the LUT varies over a surface, so that the relit texture cannot be mipmapped itself,
// the shader applies level m's own LUT to level m's texels:
//
//   LUT_m(v) = E[ mean of LUT(x) over a block | the block's mean is v ],
//
// with the expectation over the reference's own blocks. LUT_m is linear in LUT, so each
// level is one matrix, counted once per reference: LUT_m = P_m LUT (rows: block means, on the
// LUT's entries; columns: the block's base values, spread linearly over the entries the LUT
// interpolates between, so that P_m LUT is exact for the LUT as applied). Level 0 is LUT.
// (Heitz & Neyret 2018 needed per-mip LUTs for the same reason.)
//
//   MipLuts mips(bank.reference, bank.colour, bank.entries);        // per bank
//   mips.apply(channel, lut, out);      // out: levels() x entries, level 0 first

#include <vector>

#include "core/bank/lut_bank.h"
#include "core/image/image.h"

namespace btflut {

class MipLuts {
public:
    /// Levels as GenerateMipmap makes them: each halves the size (rounded down, at least 1)
    /// and averages 2 x 2 texels of the level above, down to 1 x 1.
    MipLuts(const Image& reference, ColourMode colour, int entries);

    int levels() const { return m_levels; }
    /// Channels with a matrix of their own: 3 for rgb, 1 (the grey) otherwise.
    int channels() const { return static_cast<int>(m_matrices.size()); }

    /// LUT_m for every level of one channel's LUT (`entries` values): `out` gets levels() x
    /// entries values.
    void apply(int channel, const float* lut, float* out) const;

    /// Matrices are at most this many entries square; longer LUTs (16-bit references) are
    /// resampled to it and back.
    static constexpr int kMaxMatrixSize = 256;

private:
    int m_entries = 0, m_size = 0, m_levels = 1;
    /// [channel][level - 1]: size x size, rows normalised.
    std::vector<std::vector<std::vector<float>>> m_matrices;
};

}  // namespace btflut
