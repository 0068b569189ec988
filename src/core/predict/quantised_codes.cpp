#include "core/predict/quantised_codes.h"

#include <algorithm>
#include <cmath>

namespace btflut {

QuantisedCodes QuantisedCodes::quantise(const std::vector<float>& codes, const std::vector<std::uint32_t>& inside,
                                        std::size_t N, bool truncate) {
    QuantisedCodes q;
    q.scale.assign(N, 1.f);
    q.bias.assign(N, 0.f);
    q.bytes.resize(codes.size());
    const std::size_t texels = codes.size() / N;
    for (std::size_t k = 0; k < N; ++k) {
        float low = 1e30f, high = -1e30f;
        for (std::uint32_t i : inside) {
            low = std::min(low, codes[i * N + k]);
            high = std::max(high, codes[i * N + k]);
        }
        if (high - low > 1e-6f) q.scale[k] = (high - low) / 255.f;
        q.bias[k] = -low / q.scale[k];
        for (std::size_t i = 0; i < texels; ++i) {
            const float v = std::clamp((codes[i * N + k] - low) / q.scale[k], 0.f, 255.f);
            q.bytes[i * N + k] = static_cast<std::uint8_t>(truncate ? static_cast<long>(v) : std::lround(v));
        }
    }
    return q;
}

}  // namespace btflut
