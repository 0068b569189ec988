#include "core/predict/learned_training.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "core/random.h"

namespace btflut {

void TexelSamples::read(std::size_t texel, float* out) const {
    for (const Image* image : images) {
        if (channels == 1) {
            *out++ = image->grey(texel);
        } else {
            const float* p = &image->samples[texel * 3];
            *out++ = p[0];
            *out++ = p[1];
            *out++ = p[2];
        }
    }
}

Matrix TexelSamples::block(std::span<const std::uint32_t> texels) const {
    Matrix m(static_cast<Eigen::Index>(size()), static_cast<Eigen::Index>(texels.size()));
    for (std::size_t j = 0; j < texels.size(); ++j) read(texels[j], m.col(static_cast<Eigen::Index>(j)).data());
    return m;
}

Result<TrainingSamples> drawTrainingSamples(const TexelSamples& from, const Mask& mask, std::size_t texels,
                                            std::size_t most, std::uint64_t seed, const std::string& what) {
    TrainingSamples out;
    for (std::size_t i = 0; i < texels; ++i)
        if (mask.inside.empty() || mask.inside[i]) out.inside.push_back(static_cast<std::uint32_t>(i));
    if (out.inside.empty()) return Error{what + ": the mask has no sample texels to learn from"};
    const std::size_t keep = std::min({out.inside.size(), most, kMaxSampleFloats / from.size()});
    std::vector<std::uint32_t> order = out.inside;
    Random pick(seed ^ 0x5eed);
    for (std::size_t i = 0; i < keep; ++i)  // a partial Fisher-Yates shuffle: `keep` drawn without repeats
        std::swap(order[i], order[i + pick.next() % (order.size() - i)]);
    out.texels.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep));
    std::sort(out.texels.begin(), out.texels.end());
    out.samples = from.block(out.texels);
    return out;
}

int stepBudget(int steps, std::size_t texels, std::size_t lights, double seconds, double sampleMultiplyAdds) {
    const std::size_t epoch = texels * lights / kBatchSamples + 1;
    // A time given is the time to use (more steps than the default where it allows them);
    // without one, `steps`.
    const double stepCost = 3 * std::max(1.0, sampleMultiplyAdds) * static_cast<double>(kBatchSamples) * kTrainingRuns;
    const std::size_t most = kEpochs * epoch;
    // Bounded before the cast: a time past the steps a size_t holds would not convert.
    const std::size_t asked = seconds > 0
                                  ? static_cast<std::size_t>(std::min(
                                        seconds * kTrainingMultiplyAddsPerSecond / stepCost, static_cast<double>(most)))
                                  : static_cast<std::size_t>(std::max(steps, 0));
    return static_cast<int>(std::min(asked, most));
}

Matrix decoderTarget(const Matrix& samples, Eigen::Index lights, int channels) {
    const Eigen::Index T = samples.cols(), C = channels;
    Matrix target(C, lights * T);
    for (Eigen::Index l = 0; l < lights; ++l) target.block(0, l * T, C, T) = samples.block(l * C, 0, C, T);
    return target;
}

float rateAt(int step, int steps, float peak) {
    const int warmup = std::max(1, steps / 50);
    if (step < warmup) return peak * static_cast<float>(step + 1) / static_cast<float>(warmup);
    const double t = static_cast<double>(step - warmup) / std::max(1, steps - warmup);
    return static_cast<float>(peak * (0.02 + 0.98 * 0.5 * (1 + std::cos(3.14159265358979 * t))));
}

void codesBesideLights(const Matrix& codes, const Matrix& lights, Matrix& input) {
    const Eigen::Index N = codes.rows(), T = codes.cols(), L = lights.cols(), F = lights.rows();
    input.resize(N + F, L * T);
    for (Eigen::Index l = 0; l < L; ++l) {
        input.block(0, l * T, N, T) = codes;
        input.block(N, l * T, F, T) = lights.col(l).replicate(1, T);
    }
}

Matrix codeValues(const QuantisedCodes& codes, std::span<const std::uint32_t> texels) {
    const std::size_t N = codes.count();
    Matrix values(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(texels.size()));
    for (std::size_t j = 0; j < texels.size(); ++j)
        for (std::size_t k = 0; k < N; ++k)
            values(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = codes.value(texels[j], k);
    return values;
}

std::vector<float> encodeTexels(const Network& encoder, const TexelSamples& from, std::size_t texels, int threads) {
    const auto N = static_cast<std::size_t>(encoder.outputs());
    std::vector<float> codes(texels * N);
    constexpr std::size_t kBlock = 1024;
    parallelFor((texels + kBlock - 1) / kBlock, threads, [&](std::size_t b) {
        const std::size_t begin = b * kBlock, end = std::min(texels, begin + kBlock);
        std::vector<std::uint32_t> block(end - begin);
        std::iota(block.begin(), block.end(), static_cast<std::uint32_t>(begin));
        NetworkPass pass;
        encoder.forward(from.block(block), pass);
        for (std::size_t j = 0; j < block.size(); ++j)
            for (std::size_t k = 0; k < N; ++k)
                codes[(begin + j) * N + k] = pass.output()(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j));
    });
    return codes;
}

}  // namespace btflut
