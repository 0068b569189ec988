#include "core/predict/learned_model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "core/check.h"
#include "core/parallel.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_training.h"
#include "core/predict/light_model.h"
#include "core/predict/predictor_fit.h"

namespace btflut {

std::vector<float> learnedLightFeatures(Direction light) {
    const std::vector<double> h = basisTerms(LightBasis::Hsh, 3, light);
    return {h.begin(), h.end()};
}

std::vector<float> LearnedModel::featuresAt(Direction light, Direction view) const {
    std::vector<float> f = learnedLightFeatures(light);
    if (viewFeatures > 0) {
        const std::vector<double> g = basisTerms(LightBasis::Hsh, 2, view);
        f.insert(f.end(), g.begin() + 1, g.begin() + 1 + kLearnedViewFeatures);
    }
    return f;
}

std::vector<int> LearnedModel::decoderSizes() const {
    std::vector<int> sizes{codes + features()};
    sizes.insert(sizes.end(), hidden.begin(), hidden.end());
    sizes.push_back(channels);
    return sizes;
}

std::vector<int> LearnedModel::lightSizes() const {
    std::vector<int> sizes{features()};
    sizes.insert(sizes.end(), lightHidden.begin(), lightHidden.end());
    sizes.push_back(channels * (codes + 1));
    return sizes;
}

bool LearnedModel::residualConstant() const {
    if (!decoder) return true;
    const Network& r = decoder->residual;
    return r.layers() > 0 && (r.weights(r.layers() - 1).array() == 0.f).all();
}

std::size_t LearnedModel::decoderCost() const {
    const std::vector<int> sizes = decoderSizes();
    const std::size_t n = static_cast<std::size_t>(codes) * static_cast<std::size_t>(channels);
    return residualConstant() ? n : n + Network::multiplyAddCount(sizes);
}

std::size_t LearnedModel::parameterCount(const std::vector<int>& sizes) { return Network::parameterCount(sizes); }

namespace {

// The decoder at a light over `texels` of `codes` (all `count` of them when empty).
std::vector<float> decode(const LearnedModel& m, const QuantisedCodes& codes, std::span<const std::uint32_t> texels,
                          Direction light, Direction view, int threads, std::size_t count = 0) {
    if (!texels.empty()) count = texels.size();
    if (count == 0) count = m.texels();
    const auto C = static_cast<std::size_t>(m.channels);
    const std::vector<float> h = m.featuresAt(light, view);
    const Matrix features = Eigen::Map<const Matrix>(h.data(), m.features(), 1);
    std::vector<float> out(count * C);
    constexpr std::size_t kBlock = 1024;  // fixed, so the sums do not depend on the threads
    parallelFor((count + kBlock - 1) / kBlock, threads, [&](std::size_t block) {
        const std::size_t first = block * kBlock, n = std::min(kBlock, count - first);
        std::vector<std::uint32_t> indices(n);
        for (std::size_t j = 0; j < n; ++j)
            indices[j] = static_cast<std::uint32_t>(texels.empty() ? first + j : texels[first + j]);
        LearnedDecoder::Pass pass;
        m.decoder->forward(codeValues(codes, indices), features, pass);
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t c = 0; c < C; ++c)
                out[(first + j) * C + c] =
                    std::clamp(pass.output(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(j)), 0.f, 1.f);
    });
    return out;
}

}  // namespace

std::vector<float> LearnedModel::predict(Direction light, std::span<const std::uint32_t> texels, int threads,
                                         Direction view) const {
    BTFLUT_CHECK(!empty());
    return decode(*this, quantised, texels, light, view, threads);
}

std::vector<float> LearnedModel::predictCodes(Direction light, std::vector<std::uint8_t> texelCodes, int threads,
                                              Direction view) const {
    BTFLUT_CHECK(!empty() && texelCodes.size() % static_cast<std::size_t>(codes) == 0);
    if (texelCodes.empty()) return {};
    const std::size_t count = texelCodes.size() / static_cast<std::size_t>(codes);
    const QuantisedCodes given{quantised.scale, quantised.bias, std::move(texelCodes)};
    return decode(*this, given, {}, light, view, threads, count);
}

Image LearnedModel::render(Direction light, Direction view) const {
    Image image(width, height, channels);
    image.samples = predict(light, {}, 0, view);
    return image;
}

bool LearnedModel::fitsGpu() const {
    for (const std::vector<int>* widths : {&hidden, &lightHidden}) {
        if (widths->size() > BTFLUT_LEARNED_HIDDEN) return false;
        for (int w : *widths)
            if (w > BTFLUT_LEARNED_WIDTH) return false;
    }
    return channels * (codes + 1) <= BTFLUT_LEARNED_WIDTH && codes + features() <= BTFLUT_LEARNED_WIDTH;
}

namespace {

// Values as texels of four, the last one zero-padded.
void appendTexels(std::vector<float>& out, const float* values, std::size_t count) {
    for (std::size_t k = 0; k < (count + 3) / 4 * 4; ++k) out.push_back(k < count ? values[k] : 0.f);
}

// A network's layers as btflut.glsl's btflutLearnedLayer reads them: per layer its outputs'
// rows of weights (each zero-padded to texels of four), then its biases.
void appendNetwork(std::vector<float>& out, const Network& net) {
    for (std::size_t l = 0; l < net.layers(); ++l) {
        const Matrix& w = net.weights(l);
        std::vector<float> row(static_cast<std::size_t>(w.cols()));
        for (Eigen::Index o = 0; o < w.rows(); ++o) {
            for (Eigen::Index i = 0; i < w.cols(); ++i) row[static_cast<std::size_t>(i)] = w(o, i);
            appendTexels(out, row.data(), row.size());
        }
        appendTexels(out, net.bias(l).data(), static_cast<std::size_t>(net.bias(l).size()));
    }
}

}  // namespace

LearnedModel::GpuNetwork LearnedModel::gpuNetwork() const {
    BTFLUT_CHECK(!empty() && fitsGpu());
    std::vector<float> texels{static_cast<float>(codes), static_cast<float>(channels),
                              static_cast<float>(hidden.size()), static_cast<float>(lightHidden.size())};
    for (const std::vector<int>* widths : {&hidden, &lightHidden})
        for (std::size_t k = 0; k < 4; ++k)
            texels.push_back(k < widths->size() ? static_cast<float>((*widths)[k]) : 0.f);
    texels.insert(texels.end(), {static_cast<float>(features()), 0.f, 0.f, 0.f});
    appendTexels(texels, quantised.scale.data(), quantised.scale.size());
    appendTexels(texels, quantised.bias.data(), quantised.bias.size());
    appendNetwork(texels, decoder->residual);
    appendNetwork(texels, decoder->light);
    GpuNetwork out;
    const std::size_t count = texels.size() / 4;
    out.size = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    texels.resize(static_cast<std::size_t>(out.size) * static_cast<std::size_t>(out.size) * 4, 0.f);
    out.texels = std::move(texels);
    return out;
}

LearnedModel::LightFrame LearnedModel::lightFrame(Direction light, Direction view) const {
    const Network &lightNet = decoder->light, &residual = decoder->residual;
    const std::vector<float> h = featuresAt(light, view);
    const int F = features();
    NetworkPass pass;
    lightNet.forward(Eigen::Map<const Matrix>(h.data(), F, 1), pass);
    LightFrame out;
    out.basis.assign(pass.output().data(), pass.output().data() + pass.output().size());
    const Vector first = residual.weights(0).rightCols(F) * Eigen::Map<const Vector>(h.data(), F) + residual.bias(0);
    out.hidden.assign(first.data(), first.data() + first.size());
    return out;
}

std::optional<Result<LearnedOptions>> learnedModelNamed(const std::string& name) {
    constexpr std::string_view kind = "neural";
    if (name.compare(0, kind.size(), kind) != 0) return std::nullopt;
    LearnedOptions o;
    o.seconds = kDefaultTrainingSeconds;
    // neural, neuralN, or neuralNwW: N codes (9), a residual network of two hidden layers W wide (24).
    const std::string rest = name.substr(kind.size());
    if (rest.empty()) return Result<LearnedOptions>(o);
    const std::size_t w = rest.find('w');
    const std::string codes = rest.substr(0, w), width = w == std::string::npos ? "" : rest.substr(w + 1);
    auto number = [](const std::string& digits) -> std::optional<int> {
        int n = 0;
        const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
        if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
        return n;
    };
    const std::optional<int> n = number(codes);
    if (!n || (w != std::string::npos && !number(width))) return std::nullopt;
    if (*n < 1 || *n > LearnedModel::kMaxCodes)
        return Result<LearnedOptions>(Error{"'" + name + "': a learned model has 1 to " +
                                            std::to_string(LearnedModel::kMaxCodes) + " codes per texel"});
    o.codes = *n;
    if (w != std::string::npos) {
        const int hidden = *number(width);
        if (hidden < 1 || hidden > BTFLUT_LEARNED_WIDTH)
            return Result<LearnedOptions>(Error{"'" + name + "': a learned model's hidden layers are 1 to " +
                                                std::to_string(BTFLUT_LEARNED_WIDTH) + " wide"});
        o.hidden = {hidden, hidden};
    }
    return Result<LearnedOptions>(o);
}

std::string learnedModelName(const LearnedModel& model) {
    const std::string name = "neural" + std::to_string(model.codes);
    const LearnedOptions defaults;
    if (model.hidden == defaults.hidden || model.hidden.size() != 2 || model.hidden[0] != model.hidden[1]) return name;
    return name + "w" + std::to_string(model.hidden[0]);
}

}  // namespace btflut
