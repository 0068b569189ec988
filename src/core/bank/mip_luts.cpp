#include "core/bank/mip_luts.h"

#include <algorithm>
#include <cmath>

namespace btflut {

namespace {

struct Level {
    int width, height;
    std::vector<float> values;
};

// A value in [0, 1] spread over the two entries around it: (first entry, weight of the next).
std::pair<int, float> entryOf(float v, int entries) {
    const float position = std::clamp(v, 0.f, 1.f) * static_cast<float>(entries - 1);
    const int first = std::min(static_cast<int>(position), entries - 2);
    return {first, position - static_cast<float>(first)};
}

}  // namespace

// Linear resampling of `from` values at evenly spaced points onto `to` points.
void resample(const float* in, std::size_t from, float* out, std::size_t to) {
    for (std::size_t i = 0; i < to; ++i) {
        const auto [k, f] = entryOf(static_cast<float>(i) / static_cast<float>(to - 1), static_cast<int>(from));
        out[i] = in[k] + f * (in[k + 1] - in[k]);
    }
}

MipLuts::MipLuts(const Image& reference, ColourMode colour, int entries)
    : m_entries(entries), m_size(std::min(entries, kMaxMatrixSize)) {
    BTFLUT_CHECK(entries >= 2 && !reference.samples.empty());
    const int channels = colour == ColourMode::Rgb ? 3 : 1;
    const std::size_t n = reference.pixelCount(), e = static_cast<std::size_t>(m_size);
    for (int c = 0; c < channels; ++c) {
        // The channel's base values: the grey (mean of the channels) unless rgb.
        std::vector<Level> levels{{reference.width, reference.height, std::vector<float>(n)}};
        for (std::size_t i = 0; i < n; ++i) {
            const float* p = &reference.samples[i * static_cast<std::size_t>(reference.channels)];
            if (channels == 3) {
                levels[0].values[i] = p[c];
            } else {
                float sum = 0;
                for (int k = 0; k < reference.channels; ++k) sum += p[k];
                levels[0].values[i] = sum / static_cast<float>(reference.channels);
            }
        }
        while (levels.back().width > 1 || levels.back().height > 1) {
            const Level& above = levels.back();
            Level next{std::max(1, above.width / 2), std::max(1, above.height / 2), {}};
            next.values.resize(static_cast<std::size_t>(next.width) * static_cast<std::size_t>(next.height));
            for (int y = 0; y < next.height; ++y)
                for (int x = 0; x < next.width; ++x) {
                    float sum = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx)
                            sum += above.values[static_cast<std::size_t>(std::min(2 * y + dy, above.height - 1)) *
                                                    static_cast<std::size_t>(above.width) +
                                                static_cast<std::size_t>(std::min(2 * x + dx, above.width - 1))];
                    next.values[static_cast<std::size_t>(y) * static_cast<std::size_t>(next.width) +
                                static_cast<std::size_t>(x)] = sum / 4;
                }
            levels.push_back(std::move(next));
        }
        m_levels = static_cast<int>(levels.size());
        std::vector<std::vector<float>> matrices;
        for (std::size_t m = 1; m < levels.size(); ++m) {
            const Level& level = levels[m];
            std::vector<double> p(e * e, 0.0);
            for (int y = 0; y < reference.height; ++y)
                for (int x = 0; x < reference.width; ++x) {
                    const int ax = std::min(x >> m, level.width - 1), ay = std::min(y >> m, level.height - 1);
                    const auto [row, rowNext] =
                        entryOf(level.values[static_cast<std::size_t>(ay) * static_cast<std::size_t>(level.width) +
                                             static_cast<std::size_t>(ax)],
                                m_size);
                    const auto [column, columnNext] = entryOf(
                        levels[0].values[static_cast<std::size_t>(y) * static_cast<std::size_t>(reference.width) +
                                         static_cast<std::size_t>(x)],
                        m_size);
                    const auto r = static_cast<std::size_t>(row), k = static_cast<std::size_t>(column);
                    p[r * e + k] += (1.0 - rowNext) * (1.0 - columnNext);
                    p[r * e + k + 1] += (1.0 - rowNext) * columnNext;
                    p[(r + 1) * e + k] += rowNext * (1.0 - columnNext);
                    p[(r + 1) * e + k + 1] += rowNext * columnNext;
                }
            std::vector<float> matrix(e * e, 0.f);
            for (std::size_t r = 0; r < e; ++r) {
                double sum = 0;
                for (std::size_t k = 0; k < e; ++k) sum += p[r * e + k];
                if (sum <= 0) {  // no block has this mean: the plain LUT
                    matrix[r * e + r] = 1.f;
                    continue;
                }
                for (std::size_t k = 0; k < e; ++k) matrix[r * e + k] = static_cast<float>(p[r * e + k] / sum);
            }
            matrices.push_back(std::move(matrix));
        }
        m_matrices.push_back(std::move(matrices));
    }
}

void MipLuts::apply(int channel, const float* lut, float* out) const {
    const auto entries = static_cast<std::size_t>(m_entries), e = static_cast<std::size_t>(m_size);
    std::copy_n(lut, entries, out);
    std::vector<float> in(lut, lut + entries), level(e);
    if (e != entries) resample(lut, entries, in.data(), e);
    const std::vector<std::vector<float>>& matrices = m_matrices[static_cast<std::size_t>(channel)];
    for (std::size_t m = 0; m < matrices.size(); ++m) {
        const float* p = matrices[m].data();
        for (std::size_t r = 0; r < e; ++r) {
            float sum = 0;
            for (std::size_t k = 0; k < e; ++k) sum += p[r * e + k] * in[k];
            level[r] = sum;
        }
        float* to = out + (m + 1) * entries;
        if (e == entries)
            std::copy(level.begin(), level.end(), to);
        else
            resample(level.data(), e, to, entries);
    }
}

}  // namespace btflut
