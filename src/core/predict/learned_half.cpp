#include "core/predict/learned_half.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_model.h"

namespace btflut {
namespace {

using Half = Eigen::half;  // its operators compute in float and round the result to half

Half elu(Half x) { return x > Half(0.f) ? x : Half(std::exp(static_cast<float>(x))) - Half(1.f); }

// A layer's weights, rounded once (as a shader's constants are).
std::vector<Half> halves(const float* values, std::size_t count) {
    std::vector<Half> out(count);
    for (std::size_t i = 0; i < count; ++i) out[i] = Half(values[i]);
    return out;
}

// The decoder in half precision at one light: C values per texel, clamped to [0, 1].
std::vector<float> decodeInHalf(const LearnedModel& m, Direction light, int threads) {
    const LearnedModel::LightFrame frame = m.lightFrame(light);
    const Network& residual = m.decoder->residual;
    const std::size_t N = static_cast<std::size_t>(m.codes), C = static_cast<std::size_t>(m.channels);
    const std::vector<Half> basis = halves(frame.basis.data(), frame.basis.size()),
                            first = halves(frame.hidden.data(), frame.hidden.size()),
                            scale = halves(m.quantised.scale.data(), N), bias = halves(m.quantised.bias.data(), N);
    const bool constant = m.residualConstant();
    std::vector<std::vector<Half>> weights, biases;
    for (std::size_t l = 0; l < residual.layers(); ++l) {
        const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> w = residual.weights(l);
        weights.push_back(halves(w.data(), static_cast<std::size_t>(w.size())));
        biases.push_back(halves(residual.bias(l).data(), static_cast<std::size_t>(residual.bias(l).size())));
    }
    std::vector<float> out(m.texels() * C);
    constexpr std::size_t kBlock = 4096;
    parallelFor((m.texels() + kBlock - 1) / kBlock, threads, [&](std::size_t block) {
        std::vector<Half> v(N), x, y;
        for (std::size_t t = block * kBlock; t < std::min(m.texels(), (block + 1) * kBlock); ++t) {
            for (std::size_t k = 0; k < N; ++k)
                v[k] = (Half(static_cast<float>(m.quantised.bytes[t * N + k])) - bias[k]) * scale[k];
            // The residual network: its first layer's light part and bias come with the frame.
            if (constant) {
                x = biases.back();
            } else {
                x = v;
                for (std::size_t l = 0; l < weights.size(); ++l) {
                    const std::size_t inputs = static_cast<std::size_t>(residual.weights(l).cols());
                    const std::size_t used = l == 0 ? N : inputs;  // the first layer's code inputs
                    y.assign(static_cast<std::size_t>(residual.weights(l).rows()), Half(0.f));
                    for (std::size_t o = 0; o < y.size(); ++o) {
                        Half sum = l == 0 ? first[o] : biases[l][o];
                        for (std::size_t i = 0; i < used; ++i) sum = sum + weights[l][o * inputs + i] * x[i];
                        y[o] = l + 1 < weights.size() ? elu(sum) : sum;
                    }
                    std::swap(x, y);
                }
            }
            for (std::size_t c = 0; c < C; ++c) {
                Half value = basis[c * (N + 1) + N];
                for (std::size_t k = 0; k < N; ++k) value = value + basis[c * (N + 1) + k] * v[k];
                value = value + x[c];
                out[t * C + c] = std::clamp(static_cast<float>(value), 0.f, 1.f);
            }
        }
    });
    return out;
}

}  // namespace

HalfPrecisionError halfPrecisionError(const LearnedModel& m, std::span<const Direction> lights, int threads) {
    std::vector<double> differences;
    std::size_t over = 0;
    for (Direction light : lights) {
        const std::vector<float> half = decodeInHalf(m, light, threads), full = m.predict(light, {}, threads);
        for (std::size_t i = 0; i < full.size(); ++i) {
            differences.push_back(std::abs(static_cast<double>(half[i]) - full[i]) * 255);
            if (std::abs(std::lround(half[i] * 255.f) - std::lround(full[i] * 255.f)) > 1) ++over;
        }
    }
    HalfPrecisionError e;
    if (differences.empty()) return e;
    e.max = *std::max_element(differences.begin(), differences.end());
    const auto at =
        differences.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(differences.size() - 1));
    std::nth_element(differences.begin(), at, differences.end());
    e.p99 = *at;
    e.overOneCode = static_cast<double>(over) / static_cast<double>(differences.size());
    return e;
}

}  // namespace btflut
