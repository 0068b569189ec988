#include "cli/eval/neural_rti.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"
#include "core/predict/learned_training.h"

namespace btflut {
namespace {

constexpr float kPublishedRate = 1e-2f;
constexpr std::size_t kPublishedBatch = 64;

Matrix lightPositions(const std::vector<Direction>& lights) {
    Matrix xy(2, static_cast<Eigen::Index>(lights.size()));
    for (std::size_t l = 0; l < lights.size(); ++l) {
        const Vec3 v = toVector(lights[l]);
        xy.col(static_cast<Eigen::Index>(l)) << static_cast<float>(v.x), static_cast<float>(v.y);
    }
    return xy;
}

// One thread's share of a batch: its pairs' forward and backward passes through both networks.
struct Worker {
    Matrix x, decoderInput, target, gradient, codeGradient;
    NetworkPass encoded, decoded;
    NetworkGradient encoderGradient, decoderGradient;
    double squaredError = 0;

    // Pairs [begin, end) of `pairs` (texel t of the drawn samples at light l: t L + l). With
    // `train`, the gradient of the batch's mean squared error over `batchValues` values.
    void run(const Network& encoder, const Network& decoder, const Matrix& samples, const Matrix& lights, int channels,
             const std::uint32_t* pairs, std::size_t count, bool train, double batchValues) {
        const auto L = static_cast<std::uint32_t>(lights.cols());
        const auto n = static_cast<Eigen::Index>(count), C = static_cast<Eigen::Index>(channels);
        const Eigen::Index N = encoder.outputs();
        x.resize(samples.rows(), n);
        decoderInput.resize(N + 2, n);
        target.resize(C, n);
        for (Eigen::Index j = 0; j < n; ++j) {
            const std::uint32_t t = pairs[j] / L, l = pairs[j] % L;
            x.col(j) = samples.col(t);
            decoderInput.block(N, j, 2, 1) = lights.col(l);
            target.col(j) = samples.block(l * C, t, C, 1);
        }
        encoder.forward(x, encoded);
        decoderInput.topRows(N) = encoded.output();
        decoder.forward(decoderInput, decoded);
        gradient = decoded.output() - target;
        squaredError = static_cast<double>(gradient.squaredNorm());
        if (!train) return;
        gradient *= static_cast<float>(2 / batchValues);
        decoder.backward(decoded, gradient, true, decoderGradient);
        codeGradient = decoderGradient.input.topRows(N);
        encoder.backward(encoded, codeGradient, false, encoderGradient);
    }
};

}  // namespace

bool PlateauSchedule::epochEnded(double loss) {
    // ReduceLROnPlateau: better is below the best by a relative 1e-4; a cut after 3 epochs
    // that are not, then counting again.
    if (loss < m_best * (1 - 1e-4)) {
        m_best = loss;
        m_stalled = 0;
    } else if (++m_stalled > 3) {
        m_rate *= 0.1f;
        m_stalled = 0;
    }
    // EarlyStopping: better is below the best at all; stop at the 5th epoch in a row that is not.
    if (loss < m_bestForStop) {
        m_bestForStop = loss;
        m_stalledForStop = 0;
        return true;
    }
    return ++m_stalledForStop < 5;
}

Image NeuralRti::render(Direction light) const {
    const Network net = Network::fromParameters(decoderSizes(), decoder);
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::uint32_t> all(texels);
    std::iota(all.begin(), all.end(), std::uint32_t{0});
    Matrix input;
    codesBesideLights(codeValues(quantised, all), lightPositions({light}), input);
    NetworkPass pass;
    net.forward(input, pass);
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
    if (o.maxEpochs < 1 || !(o.seconds >= 0) || !std::isfinite(o.seconds))
        return Error{what + ": NeuralRTI needs 1 epoch or more and a time bound of 0 (none) or more"};
    const Image& first = *images.front();
    NeuralRti n;
    n.width = first.width;
    n.height = first.height;
    n.codes = o.codes;
    n.channels = first.channels == 3 ? 3 : 1;
    const TexelSamples from{images, n.channels};
    Result<TrainingSamples> drawn =
        drawTrainingSamples(from, mask, first.pixelCount(), first.pixelCount(), o.seed, what);
    if (!drawn) return Error{drawn.error()};
    const auto L = static_cast<std::uint32_t>(lights.size());
    Random random(o.seed);
    Network encoder = Network::random(n.encoderSizes(static_cast<int>(L)), random, WeightInit::Torch),
            decoder = Network::random(n.decoderSizes(), random, WeightInit::Torch);
    Adam encoderAdam(encoder, true), decoderAdam(decoder, true);
    const Matrix xy = lightPositions(lights);

    // Every (texel, light) pair once, in an order drawn once; the last tenth validates.
    std::vector<std::uint32_t> pairs(drawn->texels.size() * L);
    std::iota(pairs.begin(), pairs.end(), std::uint32_t{0});
    for (std::size_t i = pairs.size(); i > 1; --i) std::swap(pairs[i - 1], pairs[random.next() % i]);
    const std::size_t validation = pairs.size() / 10, training = pairs.size() - validation;
    if (validation == 0) return Error{what + ": NeuralRTI needs 10 texel-light pairs or more to validate on"};
    const std::size_t stepsPerEpoch = (training + kPublishedBatch - 1) / kPublishedBatch;
    std::size_t mostSteps = stepsPerEpoch * static_cast<std::size_t>(o.maxEpochs);
    if (o.seconds > 0) {
        const double perPair =
            3.0 * static_cast<double>(Network::multiplyAddCount(n.encoderSizes(static_cast<int>(L))) +
                                      Network::multiplyAddCount(n.decoderSizes()));
        mostSteps = std::min(mostSteps, static_cast<std::size_t>(o.seconds * kNeuralRtiMultiplyAddsPerSecond /
                                                                 (perPair * static_cast<double>(kPublishedBatch))));
        if (mostSteps == 0)
            return Error{what + ": a time bound of " + std::to_string(o.seconds) +
                         " s trains NeuralRTI for no step; give it more"};
    }

    LockstepThreads threads(o.threads);
    std::vector<Worker> workers(static_cast<std::size_t>(threads.size()));
    // A batch's pairs split into one contiguous share per thread, summed in thread order: the
    // same sums for a seed and thread count.
    auto pass = [&](const std::uint32_t* batch, std::size_t count, bool train) {
        const std::size_t share = (count + workers.size() - 1) / workers.size();
        const double values = static_cast<double>(count) * n.channels;
        threads.run([&](int t) {
            const std::size_t begin = std::min(count, static_cast<std::size_t>(t) * share),
                              end = std::min(count, begin + share);
            workers[static_cast<std::size_t>(t)].squaredError = 0;
            if (begin < end)
                workers[static_cast<std::size_t>(t)].run(encoder, decoder, drawn->samples, xy, n.channels,
                                                         batch + begin, end - begin, train, values);
        });
        double error = 0;
        for (const Worker& w : workers) error += w.squaredError;
        if (train) {
            const std::size_t used = (count + share - 1) / share;
            for (std::size_t t = 1; t < used; ++t) {
                addGradient(workers[0].encoderGradient, workers[t].encoderGradient);
                addGradient(workers[0].decoderGradient, workers[t].decoderGradient);
            }
        }
        return error;
    };

    PlateauSchedule schedule(kPublishedRate);
    std::size_t steps = 0;
    Network bestEncoder = encoder, bestDecoder = decoder;
    double bestLoss = 1e300;
    for (int epoch = 0; epoch < o.maxEpochs && n.stopped.empty(); ++epoch) {
        double trainingError = 0;
        std::size_t trained = 0;
        for (std::size_t begin = 0; begin < training && steps < mostSteps; begin += kPublishedBatch, ++steps) {
            const std::size_t count = std::min(kPublishedBatch, training - begin);
            trainingError += pass(&pairs[begin], count, true);
            trained += count;
            if (!std::isfinite(trainingError))
                return Error{what + ": training NeuralRTI diverged (the loss is not finite at step " +
                             std::to_string(steps) + ")"};
            decoderAdam.step(decoder, workers[0].decoderGradient, schedule.rate());
            encoderAdam.step(encoder, workers[0].encoderGradient, schedule.rate());
            if (o.progress && steps % 256 == 0) o.progress(static_cast<double>(steps) / static_cast<double>(mostSteps));
        }
        double validationError = 0;
        for (std::size_t begin = training; begin < pairs.size(); begin += 1024)
            validationError += pass(&pairs[begin], std::min<std::size_t>(1024, pairs.size() - begin), false);
        NeuralRtiEpoch e;
        e.trainingLoss = trainingError / static_cast<double>(std::max<std::size_t>(trained, 1) * n.channels);
        e.validationLoss = validationError / static_cast<double>(validation * n.channels);
        e.rate = schedule.rate();
        e.steps = steps;
        n.epochs.push_back(e);
        if (!std::isfinite(e.validationLoss)) return Error{what + ": training NeuralRTI diverged"};
        if (e.validationLoss < bestLoss) {
            bestLoss = e.validationLoss;
            bestEncoder = encoder;
            bestDecoder = decoder;
            n.bestEpoch = static_cast<int>(n.epochs.size());
        }
        if (steps >= mostSteps && o.seconds > 0 && epoch + 1 < o.maxEpochs)
            n.stopped = "time bound";
        else if (!schedule.epochEnded(e.validationLoss))
            n.stopped = "early stopping";
    }
    if (n.stopped.empty()) n.stopped = std::to_string(o.maxEpochs) + " epochs";
    if (o.progress) o.progress(1);
    encoder = std::move(bestEncoder);
    decoder = std::move(bestDecoder);
    if (!encoder.finite() || !decoder.finite()) return Error{what + ": training NeuralRTI diverged"};
    n.quantised = QuantisedCodes::quantise(encodeTexels(encoder, from, first.pixelCount(), o.threads), drawn->inside,
                                           static_cast<std::size_t>(o.codes), true);
    n.decoder = decoder.parameters();
    return n;
}

}  // namespace btflut
