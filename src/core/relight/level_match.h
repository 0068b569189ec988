#pragma once
// A predictor bank's texture relit straight at a mipmap level (issue 46: skip what a scene does
// not need). A quad drawn minified 2^m times reads level m of its relit texture; relighting
// that level alone decodes 1/4^m of the texels, from level m of the predictor's planes
// (Predictor::levelCodes). The bank's own LUT would not match it: a level's prediction is not
// the level of the prediction (the learned decoder of mean codes is not the mean of decoded
// values), and a LUT of a mean is not the mean of a LUT (mip_luts.h), so the far quad's
// histogram would drift from the relit texture's own level m.
//
// So per grid node of the bank's match grid and per level, the LUT that gives the level's
// prediction the distribution of the full relit texture box-filtered to that level: the node's
// prediction through its match LUT, dithered and stored as the pass writes it, averaged over
// each level texel's square, on a sample of at most kSampleTexels of the reference's texels.
// Between nodes, the LUTs are read bilinearly, as the match grid is (Relighter::gridFrame).
// A node is made when first read (~1 full decode of the sample, once) and kept.
//
//   LevelMatch levels(bank);                          // per bank (LevelMatch::supports)
//   std::vector<float> luts = levels.luts(light, 3);  // a frame's LUTs at level 3

#include <array>
#include <map>
#include <vector>

#include "core/bank/lut_bank.h"

namespace btflut {

class LevelMatch {
public:
    /// Whether a bank's texture can be relit at a level: a view-independent predictor of one
    /// view layer with one region (the labels have no mean) and a match grid.
    static bool supports(const LutBank& bank);

    explicit LevelMatch(const LutBank& bank);  ///< `bank` must outlive it

    /// The reference's mipmap levels (GenerateMipmap's, down to 1 x 1).
    int levels() const { return m_levels; }
    /// The LUTs (channels x entries, as RelightFrame::luts) that relight level `level` at a
    /// light; level 0 is the bank's match grid read there (Relighter::gridFrame's).
    std::vector<float> luts(Direction light, int level) const;
    /// Grid node (i, j)'s LUTs at `level` > 0.
    const std::vector<float>& nodeLuts(int i, int j, int level) const;

    /// The CPU twin of relighting level `level` at a light with `luts` (luts(light, level), or
    /// any LUTs of that form): the matched channels' values (channels() per level texel, rows
    /// top first), dithered and stored as the pass writes them. Decodes the whole level.
    std::vector<float> relitLevel(Direction light, int level, const std::vector<float>& luts) const;
    /// What level `level` of the relit texture holds when the whole reference is relit and
    /// mipmapped: relitLevel at level 0, its squares averaged and stored. What luts() aims at.
    std::vector<float> filteredRelit(Direction light, int level) const;

    /// Reference texels sampled per node and level: whole level texels' squares, evenly spread.
    static constexpr std::size_t kSampleTexels = std::size_t{1} << 16;

private:
    const LutBank& m_bank;
    int m_levels = 1;
    mutable std::map<std::array<int, 3>, std::vector<float>> m_nodes;  // by (i, j, level)
};

}  // namespace btflut
