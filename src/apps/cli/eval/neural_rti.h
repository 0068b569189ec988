#pragma once
// NeuralRTI as published (Dulecha et al. 2020; univr-GRAIL's code), the baseline the learned
// kind is measured against (`btflut eval --modes neuralrti`), trained by its own recipe:
// - an encoder 3L-150-150-150-N of a texel's samples under its L lights (RGB, or grey) and a
//   decoder (N + 2)-50-50-C of the N codes and the light's (x, y); ELU; PyTorch's default
//   initialisation;
// - one sample is one (texel, training light) pair, each used once an epoch in an order drawn
//   once (its loader does not reshuffle), a random tenth of the pairs kept for validation;
// - mean squared error, Adam at 1e-2 with AMSGrad, batches of 64; the rate cut 10 times when
//   validation stalls for 4 epochs (ReduceLROnPlateau, patience 3), training stopped after 5
//   stalled epochs (EarlyStopping, patience 5), at most 30 epochs;
// - every texel encoded, each code quantised to 8 bits over its range, truncated.
// Deliberate differences, each too small to move a figure: values are [0, 1] as btflut reads
// them (v / 255, not v / 256); a capture past kMaxSampleFloats of samples trains on texels
// drawn from it (memory stays bounded: ~128 MB of samples and 4 bytes a pair); a time bound
// (`seconds`) ends training at the steps this machine runs in about that long, so that a bound
// gives the same model anywhere; a batch's gradient is summed over threads in a fixed order; the
// weights of the epoch with the best validation loss are kept, not the last epoch's (as a
// ModelCheckpoint would): at 1e-2 a late epoch can jump (dome-synth's 13th: validation MSE
// 0.0074 to 0.048), and the baseline should not lose for it.
// Not a bank's predictor.
//
//   Result<NeuralRti> n = fitNeuralRti(images, lights, mask, {}, "capture");
//   Image predicted = n->render(light);   n->epochs: its loss curve

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/predict/quantised_codes.h"
#include "core/result.h"

namespace btflut {

struct NeuralRtiOptions {
    int codes = 9;
    int maxEpochs = 30;  ///< as published
    /// Training's time bound, 0 none: the steps this machine trains in about that long
    /// (kNeuralRtiMultiplyAddsPerSecond), so that a bound gives the same model anywhere.
    double seconds = 0;
    std::uint64_t seed = 42;
    int threads = 0;
    /// Called now and then with the fraction of the most steps training may take; may be empty.
    std::function<void(double)> progress;
};

/// Multiply-adds of training a second on this machine (2 cores; a pair costs 3 times both
/// networks' forward passes: forward, backward, AMSGrad; `eval --modes neuralrti` on psm-rock
/// measured 2.0e10): what turns a time bound into steps.
constexpr double kNeuralRtiMultiplyAddsPerSecond = 2.0e10;

/// One epoch, as the published code logs it.
struct NeuralRtiEpoch {
    double trainingLoss = 0, validationLoss = 0;  ///< mean squared error per value
    float rate = 0;                               ///< Adam's rate during the epoch
    std::size_t steps = 0;                        ///< steps so far
};

/// PyTorch's ReduceLROnPlateau (mode min, factor 0.1, patience 3, relative threshold 1e-4) and
/// Lightning's EarlyStopping (patience 5) on the validation loss, as NeuralRTI trains.
class PlateauSchedule {
public:
    explicit PlateauSchedule(float rate) : m_rate(rate) {}
    float rate() const { return m_rate; }
    /// After an epoch's validation: false when training stops.
    bool epochEnded(double validationLoss);

private:
    float m_rate;
    double m_best = 1e300, m_bestForStop = 1e300;
    int m_stalled = 0, m_stalledForStop = 0;
};

struct NeuralRti {
    int width = 0, height = 0, codes = 9, channels = 1;
    QuantisedCodes quantised;            ///< N per texel, truncated to bytes as NeuralRTI stores them
    std::vector<float> decoder;          ///< (N + 2) - 50 - 50 - C, Network::parameters' order
    std::vector<NeuralRtiEpoch> epochs;  ///< the loss curve; the last may be cut short by the time bound
    std::string stopped;                 ///< why training ended: "early stopping", "30 epochs", "time bound"
    int bestEpoch = 0;                   ///< the epoch (1 the first) whose weights are kept: the best validation

    std::vector<int> decoderSizes() const { return {codes + 2, 50, 50, channels}; }
    std::vector<int> encoderSizes(int lights) const { return {lights * channels, 150, 150, 150, codes}; }
    Image render(Direction light) const;
};

/// Trains it on images of one view under `lights` (RGB or grey; 3 lights at least).
Result<NeuralRti> fitNeuralRti(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                               const Mask& mask, const NeuralRtiOptions& options, const std::string& what);

}  // namespace btflut
