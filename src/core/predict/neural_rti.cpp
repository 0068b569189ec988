#include "core/predict/neural_rti.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/predict/learned_training.h"

namespace btflut {
namespace {

constexpr float kPublishedRate = 1e-3f;  // Adam's, as published

// The decoder's input for texels x lights, light-major: each code beside the light's x, y.
Matrix decoderInput(const Matrix& codes, const Matrix& lights) {
    Matrix input;
    codesBesideLights(codes, lights, input);
    return input;
}

Matrix lightPositions(const std::vector<Direction>& lights) {
    Matrix xy(2, static_cast<Eigen::Index>(lights.size()));
    for (std::size_t l = 0; l < lights.size(); ++l) {
        const Vec3 v = toVector(lights[l]);
        xy.col(static_cast<Eigen::Index>(l)) << static_cast<float>(v.x), static_cast<float>(v.y);
    }
    return xy;
}

}  // namespace

Image NeuralRti::render(Direction light) const {
    const Network net = Network::fromParameters(decoderSizes(), decoder);
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::uint32_t> all(texels);
    std::iota(all.begin(), all.end(), std::uint32_t{0});
    const Matrix values = codeValues(coefficients, scale, bias, all);
    NetworkPass pass;
    net.forward(decoderInput(values, lightPositions({light})), pass);
    Image image(width, height, channels);
    for (std::size_t i = 0; i < texels; ++i)
        for (int c = 0; c < channels; ++c)
            image.samples[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] =
                std::clamp(pass.output()(c, static_cast<Eigen::Index>(i)), 0.f, 1.f);
    return image;
}

Result<NeuralRti> fitNeuralRti(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                               const Mask& mask, const NeuralRtiOptions& o, const std::string& what) {
    if (images.size() != lights.size() || images.size() < 3) return Error{what + ": NeuralRTI needs 3 lights or more"};
    const Image& first = *images.front();
    NeuralRti n;
    n.width = first.width;
    n.height = first.height;
    n.codes = o.codes;
    n.channels = first.channels == 3 ? 3 : 1;
    const TexelSamples from{images, n.channels};
    Result<TrainingSamples> drawn =
        drawTrainingSamples(from, mask, first.pixelCount(), std::size_t{1} << 15, o.seed, what);
    if (!drawn) return Error{drawn.error()};
    const int D = static_cast<int>(from.size());
    Random random(o.seed);
    Network encoder = Network::random({D, D, D, D, o.codes}, random),
            decoder = Network::random(n.decoderSizes(), random);
    Adam encoderAdam(encoder), decoderAdam(decoder);
    const Matrix lights2 = lightPositions(lights);
    const std::size_t L = lights.size(), T = drawn->texels.size(),
                      perBatch = std::max<std::size_t>(1, kBatchSamples / L);
    const int steps = stepBudget(o.steps, T, L);
    Matrix x(D, static_cast<Eigen::Index>(perBatch)), gradient,
        codeGradient(o.codes, static_cast<Eigen::Index>(perBatch));
    NetworkPass encoded, decoded;
    for (int step = 0; step < steps; ++step) {
        for (std::size_t j = 0; j < perBatch; ++j)
            x.col(static_cast<Eigen::Index>(j)) = drawn->samples.col(static_cast<Eigen::Index>(random.next() % T));
        encoder.forward(x, encoded);
        decoder.forward(decoderInput(encoded.output(), lights2), decoded);
        if (!std::isfinite(
                squaredError(decoded.output(), decoderTarget(x, static_cast<Eigen::Index>(L), n.channels), gradient)))
            return Error{what + ": training NeuralRTI diverged (the loss is not finite)"};
        const NetworkGradient g = decoder.backward(decoded, gradient, true);
        for (std::size_t j = 0; j < perBatch; ++j) codeGradient.col(static_cast<Eigen::Index>(j)).setZero();
        for (std::size_t l = 0; l < L; ++l)
            codeGradient +=
                g.input.block(0, static_cast<Eigen::Index>(l * perBatch), o.codes, static_cast<Eigen::Index>(perBatch));
        const NetworkGradient e = encoder.backward(encoded, codeGradient, false);
        const float rate = rateAt(step, steps, kPublishedRate);
        decoderAdam.step(decoder, g, rate);
        encoderAdam.step(encoder, e, rate);
    }
    if (!encoder.finite() || !decoder.finite()) return Error{what + ": training NeuralRTI diverged"};
    quantiseCodes(encodeTexels(encoder, from, first.pixelCount(), o.threads), drawn->inside,
                  static_cast<std::size_t>(o.codes), n.scale, n.bias, n.coefficients);
    n.decoder = decoder.parameters();
    return n;
}

}  // namespace btflut
