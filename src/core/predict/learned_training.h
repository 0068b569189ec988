#pragma once
// What training a learned model (learned_fit.cpp) and eval's published NeuralRTI baseline
// (src/apps/cli/eval/neural_rti.h) share: the texels' samples, the batches, the loss, the
// rate's schedule, the codes of every texel and their 8-bit quantisation.

#include <span>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/learn/network.h"
#include "core/predict/quantised_codes.h"
#include "core/result.h"

namespace btflut {

constexpr std::size_t kBatchSamples = 2048;         ///< texel-light samples per step
constexpr std::size_t kMaxSampleFloats = 1u << 25;  ///< 128 MB of training samples at most
constexpr std::size_t kEpochs = 50;                 ///< passes over the samples at most

/// The values a texel's code is made from: its samples under every light, lights x channels
/// (light-major).
struct TexelSamples {
    const std::vector<const Image*>& images;
    int channels;  ///< 1: the grey value; 3: RGB
    std::size_t size() const { return images.size() * static_cast<std::size_t>(channels); }
    void read(std::size_t texel, float* out) const;
    Matrix block(std::span<const std::uint32_t> texels) const;
};

/// The texels trained on: drawn with the seed from the mask (all texels when it is empty), at
/// most `most` and at most kMaxSampleFloats floats of samples; sorted.
struct TrainingSamples {
    std::vector<std::uint32_t> inside;  ///< every texel of the mask
    std::vector<std::uint32_t> texels;  ///< the drawn ones
    Matrix samples;                     ///< their samples, one column each
};
Result<TrainingSamples> drawTrainingSamples(const TexelSamples& from, const Mask& mask, std::size_t texels,
                                            std::size_t most, std::uint64_t seed, const std::string& what);

/// Multiply-adds of training a second when a time bounds it: this machine's 2 cores, a batch's
/// shards on both (a sample costs 3 times its forward pass: forward, backward, Adam; dome-synth's
/// neural9 measured 1.4e10), rounded down, so a bound gives the same steps, and the same bank,
/// wherever it is baked.
constexpr double kTrainingMultiplyAddsPerSecond = 1.2e10;
/// A fit's training runs, in units of one run's steps: the validated run, the run on every
/// light (as long at most) and the tuning to quantised codes (a fifth). The second validated
/// run (learned_fit.cpp: one per weight decay) is not priced, so that a decay of 0.1 chosen
/// gives the bank it gave before the choice: a fit takes up to 3.2 / 2.2 of its time.
constexpr double kTrainingRuns = 2.2;

/// Steps to train: `steps`, or when `seconds` > 0 what trains in about that long, a sample's
/// forward pass costing `sampleMultiplyAdds` (a time given is used, beyond the default steps);
/// at most kEpochs passes over the samples (a small capture trains in proportion).
int stepBudget(int steps, std::size_t texels, std::size_t lights, double seconds = 0, double sampleMultiplyAdds = 0);

/// The samples of a batch's texels as decoders order them (light-major: l T + t), C x L T.
Matrix decoderTarget(const Matrix& samples, Eigen::Index lights, int channels);
/// Cosine decay from `peak` after a short warm-up.
float rateAt(int step, int steps, float peak);

/// Codes beside lights, as decoders take them: column l T + t is texel t's code above light
/// l's features (light-major), written into `input` (its storage kept between steps).
void codesBesideLights(const Matrix& codes, const Matrix& lights, Matrix& input);
/// The values of `texels`' stored codes, one column each: (byte - bias) scale.
Matrix codeValues(const QuantisedCodes& codes, std::span<const std::uint32_t> texels);

/// Every texel's code (N per texel) from the encoder over its samples, in blocks of a fixed
/// size (the same sums on any thread count).
std::vector<float> encodeTexels(const Network& encoder, const TexelSamples& from, std::size_t texels, int threads);

}  // namespace btflut
