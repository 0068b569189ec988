#pragma once
// The learned predictor's data (docs/predictors.md, "The learned kind"): per texel N codes
// (bytes; code k's value is (byte_k - bias_k) scale_k, one scale and bias per code as RTI web
// formats store them) and one small decoder network per bank that takes a texel's code values
// and the light's (x, y) to its colour (NeuralRTI's form, Dulecha et al. 2020):
//
//   pred_c = clamp(sum_k A_ck(L) v_k + a_c(L) + r_c(v_1 .. v_N, h(L)), 0, 1)
//
// h(L) the light's order-3 hemispherical harmonics (smooth between the measured lights, as
// hsh3 is). A and a, a linear basis of the codes, come from a light network of h run once per
// light; r, a residual network of ELU layers, adds what a linear basis cannot
// (learned_decoder.h).
//
// Trained at bake time (learned_fit.cpp): each texel's code is a learned linear function of
// its samples under the training lights (started from their principal components), trained
// jointly with the decoder on sampled texels, then quantised to 8 bits and the decoder tuned
// to the quantised codes.
//
//   Result<LearnedModel> m = fitLearnedModel(images, lights, mask, {.codes = 9}, "capture");
//   Image predicted = m->render(light);

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/predict/quantised_codes.h"
#include "core/result.h"

namespace btflut {

struct LearnedDecoder;  // learned_decoder.h: its networks (Eigen's, which this header keeps out)

/// The light's features h(L) both networks take: its 9 hemispherical harmonics of order 3.
constexpr int kLearnedLightFeatures = 9;
std::vector<float> learnedLightFeatures(Direction light);
/// A model of rectified views (eval across views) also takes the view's: its hemispherical
/// harmonics of order 2 but the constant (the light's has it).
constexpr int kLearnedViewFeatures = 3;

struct LearnedModel {
    static constexpr int kMaxCodes = 16;
    static constexpr int kMaxParameters = 8192;  ///< each network's: small enough for a fragment shader

    int width = 0, height = 0;
    int codes = 0;     ///< N, bytes per texel, 1..kMaxCodes
    int channels = 1;  ///< the decoder's outputs: 1 (grey) or 3 (RGB)
    /// 0, or kLearnedViewFeatures for a model of rectified views, whose networks also take
    /// the view (a bank of such a model has a view layer per measured view).
    int viewFeatures = 0;
    QuantisedCodes quantised;  ///< the texels' N codes as bytes: v_k = (byte_k - bias_k) scale_k
    /// The decoder's networks' hidden widths: the light network's and the residual network's.
    std::vector<int> lightHidden, hidden;
    /// The decoder (learned_decoder.h), built once (its networks of lightSizes() and
    /// decoderSizes()) and shared by the model's copies.
    std::shared_ptr<const LearnedDecoder> decoder;

    bool empty() const { return quantised.empty(); }
    /// F, the features both networks take, and their values for a light (and a view).
    int features() const { return kLearnedLightFeatures + viewFeatures; }
    std::vector<float> featuresAt(Direction light, Direction view = {}) const;
    std::size_t texels() const { return static_cast<std::size_t>(width) * height; }
    /// The residual network's layer sizes: N + F inputs, the hidden widths, `channels` outputs.
    std::vector<int> decoderSizes() const;
    /// The light network's: F inputs, its hidden widths, channels (N + 1) outputs.
    std::vector<int> lightSizes() const;
    /// Whether the residual network adds only a constant: its last layer's weights are all zero
    /// (it trains from zero, and validation can keep the linear start), so decoders skip it.
    bool residualConstant() const;
    /// Multiply-adds per texel and light: the linear basis's and the residual network's (none
    /// when it is constant).
    std::size_t decoderCost() const;
    /// The parameters of a decoder of these layer sizes (weights and biases).
    static std::size_t parameterCount(const std::vector<int>& sizes);

    /// The prediction of `texels` (all of them when empty) at a light: channels floats per
    /// texel in [0, 1], in the order given. Evaluated in blocks of a fixed size, so the
    /// result does not depend on `threads`.
    std::vector<float> predict(Direction light, std::span<const std::uint32_t> texels = {}, int threads = 1,
                               Direction view = {}) const;
    /// The same for texels whose codes are given (N bytes each, as `quantised` holds them)
    /// rather than the model's own: a mipmap level's (LearnedPredictor::levelCodes). Taken by
    /// value: they become the bytes of a QuantisedCodes of the model's scale and bias.
    std::vector<float> predictCodes(Direction light, std::vector<std::uint8_t> codes, int threads = 1,
                                    Direction view = {}) const;
    /// The prediction as an image (grey or RGB, float); `view` for a model of views.
    Image render(Direction light, Direction view = {}) const;

    /// Whether a GPU's decoder evaluates it (shaders/btflut.glsl's arrays): at most
    /// BTFLUT_LEARNED_HIDDEN hidden layers per network, none wider than BTFLUT_LEARNED_WIDTH.
    /// The networks `bake` trains fit.
    bool fitsGpu() const;
    /// The decoder as a GPU reads it (btflut.glsl, "A learned model"): RGBA32F texels, a square
    /// of `size` a side, row by row: a head (N, C, the hidden layer counts and widths), the
    /// F (the features) in a fourth, the codes' scale and bias, the residual network's layers,
    /// the light network's.
    struct GpuNetwork {
        int size = 0;
        std::vector<float> texels;  ///< size x size x 4
    };
    GpuNetwork gpuNetwork() const;
    /// Its per-light (and per-view) part, what the GPU reads as uniforms: the light network's outputs (the
    /// linear basis: C (N + 1), row c (N + 1) + k is A_ck, row c (N + 1) + N is a_c) and the
    /// residual network's first layer at codes 0 and the light's features (its bias included).
    struct LightFrame {
        std::vector<float> basis, hidden;
    };
    LightFrame lightFrame(Direction light, Direction view = {}) const;
};

struct LearnedOptions {
    int codes = 9;
    std::vector<int> hidden{24, 24};  ///< the residual network's
    std::vector<int> lightHidden;     ///< the light network's (none: linear in h)
    bool colour = true;               ///< predict RGB (the images' colour); else grey
    std::uint64_t seed = 1;
    /// Texels trained on, drawn from the mask: memory holds their samples (lights x channels
    /// floats each) and nothing else per image beyond the decoded images themselves.
    std::size_t sampleTexels = std::size_t{1} << 15;
    int steps = 6000;  ///< Adam steps of about 2048 texel-light samples
    /// Training's time bound, 0 none: the steps the trainer runs in about that long on this
    /// machine (learned_training.h, kTrainingMultiplyAddsPerSecond), so the bank is the same
    /// anywhere.
    double seconds = 0;
    float rate = 0.02f;  ///< Adam's peak rate (the residual network's; the linear parts' 1/20)
    /// The residual network's decoupled weight decay: validation chooses among these (a first
    /// run each; the first kept on a tie). How smooth between the lights it must be depends
    /// on the capture (learned_fit.cpp).
    std::vector<float> weightDecays{0.1f, 0.01f};
    int threads = 0;
    /// Called now and then with the fraction done (0..1); may be empty.
    std::function<void(double)> progress;
};

/// Trains a model on images of one view under `lights` (same size; RGB or grey), or with
/// `views` (one per image) on rectified images of several views, the networks taking the view
/// too. Refuses fewer than 3 lights, codes or hidden widths out of range, an empty mask and
/// training that diverges after two retries (`what` names the dataset).
Result<LearnedModel> fitLearnedModel(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                     const Mask& mask, const LearnedOptions& options, const std::string& what,
                                     const std::vector<Direction>& views = {});

/// The options from a `--predictor` name: neural (9 codes), neuralN (N codes) or neuralNwW (N
/// codes, the residual network's two hidden layers W wide; 24 otherwise); nothing when the name
/// is not one of these, an error for a number out of range.
std::optional<Result<LearnedOptions>> learnedModelNamed(const std::string& name);
std::string learnedModelName(const LearnedModel& model);

}  // namespace btflut
