#include "core/relight/level_match.h"

#include <cmath>

#include "core/check.h"
#include "core/histogram/lut.h"

namespace btflut {

namespace {

// A texel of code `code` relit through `lut` as the pass writes it: dithered at (x, y) and
// stored in the target's codes (the value's code, 0 .. 1 / outCode).
double storedCode(std::size_t code, std::uint32_t x, std::uint32_t y, std::uint32_t channel, const float* lut,
                  int entries, float inCode, float outCode) {
    const float v = static_cast<float>(code + 1) * inCode;
    return std::round(lutOutput(Lut::applyLut(lut, entries, lutInput(v, x, y, inCode, channel)), outCode) / outCode);
}

}  // namespace

bool LevelMatch::supports(const LutBank& bank) {
    return bank.makesLuts() && bank.layers.size() == 1 && !bank.predictor().viewDependent() &&
           bank.prediction.regions == 1 && !bank.layers[0].matchGridLuts.empty();
}

LevelMatch::LevelMatch(const LutBank& bank)
    : m_bank(bank), m_levels(levelCount(bank.reference.width, bank.reference.height)) {
    BTFLUT_CHECK(supports(bank));
}

std::vector<float> LevelMatch::luts(Direction light, int level) const {
    BTFLUT_CHECK(level >= 0 && level < m_levels);
    if (level == 0) return m_bank.matchGridLookup(light, std::size_t{0});
    const GridCell cell = gridCellAt(toDisk(light), m_bank.gridSize);
    const auto size = static_cast<std::size_t>(m_bank.gridSize);
    std::vector<float> out(m_bank.matchLength(), 0.f);
    for (std::size_t n = 0; n < 4; ++n) {
        const std::vector<float>& node =
            nodeLuts(static_cast<int>(cell.node[n] % size), static_cast<int>(cell.node[n] / size), level);
        for (std::size_t k = 0; k < out.size(); ++k) out[k] += static_cast<float>(cell.weight[n] * node[k]);
    }
    return out;
}

const std::vector<float>& LevelMatch::nodeLuts(int i, int j, int level) const {
    BTFLUT_CHECK(level > 0 && level < m_levels);
    auto found = m_nodes.find({i, j, level});
    if (found != m_nodes.end()) return found->second;

    const LutBank& bank = m_bank;
    const Predictor& predictor = bank.predictor();
    const int width = bank.reference.width, height = bank.reference.height;
    const PredictorFrame frame = predictor.frameAt(fromDisk(bank.gridPoint(i, j)), bank.layers[0].view);

    // Whole level texels, evenly spread, and the reference's texels under them.
    const std::size_t levelTexels =
        static_cast<std::size_t>(levelSize(width, level)) * static_cast<std::size_t>(levelSize(height, level));
    const std::size_t sampled = std::min(levelTexels, std::max<std::size_t>(1, kSampleTexels >> (2 * level)));
    std::vector<std::uint32_t> blocks(sampled), texels;
    std::vector<std::size_t> firstTexel{0};
    for (std::size_t s = 0; s < sampled; ++s) {
        blocks[s] = static_cast<std::uint32_t>(s * levelTexels / sampled);
        const std::vector<std::uint32_t> block = levelBlock(level, width, height, blocks[s]);
        texels.insert(texels.end(), block.begin(), block.end());
        firstTexel.push_back(texels.size());
    }
    std::vector<std::size_t> fine, coarse;  // codes, channels() per texel
    predictor.levelCodes(frame, 0, width, height, texels, fine);
    predictor.levelCodes(frame, level, width, height, blocks, coarse);

    const auto channels = static_cast<std::size_t>(predictor.channels()),
               entries = static_cast<std::size_t>(bank.entries);
    BTFLUT_CHECK(channels * entries == bank.matchLength());
    const std::size_t cell =
        static_cast<std::size_t>(j) * static_cast<std::size_t>(bank.gridSize) + static_cast<std::size_t>(i);
    const std::uint16_t* grid = &bank.layers[0].matchGridLuts[cell * bank.matchLength()];
    const float inCode = 1.f / static_cast<float>(predictor.codes() + 1), outCode = bank.targetCode();
    const auto outCodes = static_cast<std::size_t>(std::lround(1.0 / outCode));
    const int quantiles = std::max(bank.prediction.quantiles, 1024);

    std::vector<float> luts;
    std::vector<float> lut(entries);
    for (std::size_t c = 0; c < channels; ++c) {
        for (std::size_t k = 0; k < entries; ++k) lut[k] = static_cast<float>(grid[c * entries + k] / 65535.0);
        // The relit texture's level: each texel as the pass writes it (dithered, stored in the
        // target's codes), averaged over the square and stored again.
        LevelCounts target, predicted;
        target.counts.assign(outCodes + 1, 0);
        predicted.counts.assign(static_cast<std::size_t>(predictor.codes()) + 2, 0);
        for (std::size_t s = 0; s < sampled; ++s) {
            double sum = 0;
            for (std::size_t t = firstTexel[s]; t < firstTexel[s + 1]; ++t)
                sum += storedCode(fine[t * channels + c], texels[t] % static_cast<std::uint32_t>(width),
                                  texels[t] / static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(c),
                                  lut.data(), bank.entries, inCode, outCode);
            const auto mean =
                static_cast<std::size_t>(std::lround(sum / static_cast<double>(firstTexel[s + 1] - firstTexel[s])));
            ++target.counts[std::min(mean, outCodes)];
            ++predicted.counts[coarse[s * channels + c] + 1];
        }
        const Lut matched = matchToQuantiles(predicted, quantileFunction(target, quantiles), bank.entries);
        luts.insert(luts.end(), matched.values.begin(), matched.values.end());
    }
    return m_nodes.emplace(std::array<int, 3>{i, j, level}, std::move(luts)).first->second;
}

std::vector<float> LevelMatch::relitLevel(Direction light, int level, const std::vector<float>& luts) const {
    const LutBank& bank = m_bank;
    const Predictor& predictor = bank.predictor();
    const int width = bank.reference.width, height = bank.reference.height;
    const int levelWidth = levelSize(width, level);
    std::vector<std::uint32_t> texels(static_cast<std::size_t>(levelWidth) *
                                      static_cast<std::size_t>(levelSize(height, level)));
    for (std::size_t t = 0; t < texels.size(); ++t) texels[t] = static_cast<std::uint32_t>(t);
    std::vector<std::size_t> codes;
    predictor.levelCodes(predictor.frameAt(light, bank.layers[0].view), level, width, height, texels, codes);
    const auto channels = static_cast<std::size_t>(predictor.channels()),
               entries = static_cast<std::size_t>(bank.entries);
    const float inCode = 1.f / static_cast<float>(predictor.codes() + 1), outCode = bank.targetCode();
    std::vector<float> out(codes.size());
    for (std::size_t t = 0; t < texels.size(); ++t)
        for (std::size_t c = 0; c < channels; ++c)
            out[t * channels + c] = static_cast<float>(
                storedCode(codes[t * channels + c], texels[t] % static_cast<std::uint32_t>(levelWidth),
                           texels[t] / static_cast<std::uint32_t>(levelWidth), static_cast<std::uint32_t>(c),
                           &luts[c * entries], bank.entries, inCode, outCode) *
                outCode);
    return out;
}

std::vector<float> LevelMatch::filteredRelit(Direction light, int level) const {
    const LutBank& bank = m_bank;
    const int width = bank.reference.width, height = bank.reference.height;
    const std::vector<float> fine = relitLevel(light, 0, luts(light, 0));
    const auto channels = static_cast<std::size_t>(bank.predictor().channels());
    const std::size_t texels =
        static_cast<std::size_t>(levelSize(width, level)) * static_cast<std::size_t>(levelSize(height, level));
    const float outCode = bank.targetCode();
    std::vector<float> out(texels * channels);
    for (std::size_t t = 0; t < texels; ++t) {
        const std::vector<std::uint32_t> block = levelBlock(level, width, height, static_cast<std::uint32_t>(t));
        for (std::size_t c = 0; c < channels; ++c) {
            double sum = 0;
            for (std::uint32_t b : block) sum += fine[b * channels + c];
            out[t * channels + c] =
                static_cast<float>(std::round(sum / static_cast<double>(block.size()) / outCode) * outCode);
        }
    }
    return out;
}

}  // namespace btflut
