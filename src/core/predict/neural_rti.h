#pragma once
// NeuralRTI as published (Dulecha et al. 2020), the baseline the learned kind is measured
// against (`btflut eval --modes neuralrti`): an encoder of 3 ELU layers as wide as a texel's
// samples (lights x channels) to N = 9 codes, the codes stored with 8 bits each, and an ELU
// decoder (N + 2) - 50 - 50 - C of the codes and the light's (x, y). Trained together by Adam
// on the same sampled texels and steps as the learned kind (learned_training.h); not a
// bank's predictor.
//
//   Result<NeuralRti> n = fitNeuralRti(images, lights, mask, {}, "capture");
//   Image predicted = n->render(light);

#include <cstdint>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/result.h"

namespace btflut {

struct NeuralRtiOptions {
    int codes = 9;
    int steps = 6000;  ///< as the learned kind's, at most 50 passes over the samples
    std::uint64_t seed = 1;
    int threads = 0;
};

struct NeuralRti {
    int width = 0, height = 0, codes = 9, channels = 1;
    std::vector<float> scale, bias;          ///< per code: value = (byte - bias) scale
    std::vector<std::uint8_t> coefficients;  ///< N per texel
    std::vector<float> decoder;              ///< (N + 2) - 50 - 50 - C, Network::parameters' order

    std::vector<int> decoderSizes() const { return {codes + 2, 50, 50, channels}; }
    Image render(Direction light) const;
};

/// Trains it on images of one view under `lights` (RGB or grey; 3 lights at least).
Result<NeuralRti> fitNeuralRti(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                               const Mask& mask, const NeuralRtiOptions& options, const std::string& what);

}  // namespace btflut
