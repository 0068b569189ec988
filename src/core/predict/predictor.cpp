#include "core/predict/predictor.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/check.h"

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

void levelTexelBytes(std::span<const std::uint8_t> bytes, int width, int height, int channels, int level,
                     std::uint32_t texel, std::uint8_t* out) {
    const auto C = static_cast<std::size_t>(channels);
    const int side = 1 << level, levelWidth = levelSize(width, level);
    const int x0 = static_cast<int>(texel % static_cast<std::uint32_t>(levelWidth)) * side,
              y0 = static_cast<int>(texel / static_cast<std::uint32_t>(levelWidth)) * side;
    const int x1 = std::min(x0 + side, width), y1 = std::min(y0 + side, height);
    for (std::size_t c = 0; c < C; ++c) {
        std::uint32_t sum = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                sum += bytes[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(x)) *
                                 C +
                             c];
        out[c] = meanByte(sum, static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0));
    }
}

std::vector<std::uint8_t> levelOfBytes(std::span<const std::uint8_t> bytes, int width, int height, int channels,
                                       int level) {
    const auto C = static_cast<std::size_t>(channels);
    const std::size_t texels =
        static_cast<std::size_t>(levelSize(width, level)) * static_cast<std::size_t>(levelSize(height, level));
    std::vector<std::uint8_t> out(texels * C);
    for (std::size_t t = 0; t < texels; ++t)
        levelTexelBytes(bytes, width, height, channels, level, static_cast<std::uint32_t>(t), &out[t * C]);
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

std::vector<float> weightsInLayers(const std::vector<float>& grid, std::size_t count, int size) {
    const std::size_t nodes = static_cast<std::size_t>(size) * static_cast<std::size_t>(size), layers = (count + 3) / 4;
    BTFLUT_CHECK(grid.size() == nodes * count);
    std::vector<float> out(layers * nodes * 4, 0.f);
    for (std::size_t n = 0; n < nodes; ++n)
        for (std::size_t k = 0; k < count; ++k) out[((k / 4) * nodes + n) * 4 + k % 4] = grid[n * count + k];
    return out;
}

nlohmann::json atlasImages(const std::vector<Image>& images, const std::string& prefix, const TextureWriter& texture) {
    nlohmann::json names = nlohmann::json::array();
    for (std::size_t k = 0; k < images.size(); ++k)
        names.push_back(texture(prefix + "-" + std::to_string(k), images[k]));
    return names;
}

}  // namespace btflut
