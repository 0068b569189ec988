#include "core/predict/predictor.h"

#include <cmath>

namespace btflut {

std::vector<std::uint32_t> levelBlock(int level, int width, int height, std::uint32_t texel) {
    const auto side = std::uint32_t{1} << level, levelWidth = static_cast<std::uint32_t>(levelSize(width, level));
    const std::uint32_t x0 = texel % levelWidth * side, y0 = texel / levelWidth * side;
    std::vector<std::uint32_t> block;
    for (std::uint32_t y = y0; y < std::min(y0 + side, static_cast<std::uint32_t>(height)); ++y)
        for (std::uint32_t x = x0; x < std::min(x0 + side, static_cast<std::uint32_t>(width)); ++x)
            block.push_back(y * static_cast<std::uint32_t>(width) + x);
    return block;
}

std::vector<std::uint8_t> levelOfBytes(std::span<const std::uint8_t> bytes, int width, int height, int channels,
                                       int level) {
    // levelBlock's squares, summed in place (a texture's every texel once per level).
    const auto C = static_cast<std::size_t>(channels);
    const int levelWidth = levelSize(width, level), levelHeight = levelSize(height, level), side = 1 << level;
    std::vector<std::uint8_t> out(static_cast<std::size_t>(levelWidth) * static_cast<std::size_t>(levelHeight) * C);
    std::vector<std::uint32_t> sums(C);
    for (int y = 0; y < levelHeight; ++y)
        for (int x = 0; x < levelWidth; ++x) {
            std::fill(sums.begin(), sums.end(), 0u);
            const int x1 = std::min((x + 1) * side, width), y1 = std::min((y + 1) * side, height);
            for (int by = y * side; by < y1; ++by)
                for (int bx = x * side; bx < x1; ++bx)
                    for (std::size_t c = 0; c < C; ++c)
                        sums[c] += bytes[(static_cast<std::size_t>(by) * static_cast<std::size_t>(width) +
                                          static_cast<std::size_t>(bx)) *
                                             C +
                                         c];
            const auto count = static_cast<std::size_t>(x1 - x * side) * static_cast<std::size_t>(y1 - y * side);
            for (std::size_t c = 0; c < C; ++c)
                out[(static_cast<std::size_t>(y) * static_cast<std::size_t>(levelWidth) + static_cast<std::size_t>(x)) *
                        C +
                    c] = meanByte(sums[c], count);
        }
    return out;
}

void Predictor::levelCodes(const PredictorFrame& frame, int level, int width, int height,
                           std::span<const std::uint32_t> texels, std::vector<std::size_t>& codes) const {
    const auto C = static_cast<std::size_t>(channels());
    codes.resize(texels.size() * C);
    for (std::size_t j = 0; j < texels.size(); ++j)
        for (std::size_t c = 0; c < C; ++c) {
            if (level == 0) {
                codes[j * C + c] = code(frame, texels[j], static_cast<int>(c));
                continue;
            }
            double sum = 0;
            const std::vector<std::uint32_t> block = levelBlock(level, width, height, texels[j]);
            for (std::uint32_t t : block) sum += static_cast<double>(code(frame, t, static_cast<int>(c)));
            codes[j * C + c] = static_cast<std::size_t>(std::lround(sum / static_cast<double>(block.size())));
        }
}

}  // namespace btflut
