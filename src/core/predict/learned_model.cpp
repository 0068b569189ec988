#include "core/predict/learned_model.h"

#include <algorithm>
#include <charconv>

#include "core/check.h"
#include "core/parallel.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_training.h"
#include "core/predict/light_model.h"

namespace btflut {

std::vector<float> learnedLightFeatures(Direction light) {
    const std::vector<double> h = basisTerms(LightBasis::Hsh, 3, light);
    return {h.begin(), h.end()};
}

std::vector<int> LearnedModel::decoderSizes() const {
    std::vector<int> sizes{codes + kLearnedLightFeatures};
    sizes.insert(sizes.end(), hidden.begin(), hidden.end());
    sizes.push_back(channels);
    return sizes;
}

std::vector<int> LearnedModel::lightSizes() const {
    std::vector<int> sizes{kLearnedLightFeatures};
    sizes.insert(sizes.end(), lightHidden.begin(), lightHidden.end());
    sizes.push_back(channels * (codes + 1));
    return sizes;
}

std::size_t LearnedModel::decoderCost() const {
    const std::vector<int> sizes = decoderSizes();
    std::size_t n = static_cast<std::size_t>(codes) * static_cast<std::size_t>(channels);
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k) n += static_cast<std::size_t>(sizes[k]) * sizes[k + 1];
    return n;
}

std::size_t LearnedModel::parameterCount(const std::vector<int>& sizes) { return Network::parameterCount(sizes); }

std::vector<float> LearnedModel::predict(Direction light, std::span<const std::uint32_t> texels, int threads) const {
    BTFLUT_CHECK(!empty());
    const LearnedDecoder net{Network::fromParameters(lightSizes(), lightNetwork),
                             Network::fromParameters(decoderSizes(), decoder)};
    const std::size_t count = texels.empty() ? this->texels() : texels.size(), C = static_cast<std::size_t>(channels);
    const std::vector<float> h = learnedLightFeatures(light);
    const Matrix features = Eigen::Map<const Matrix>(h.data(), kLearnedLightFeatures, 1);
    std::vector<float> out(count * C);
    constexpr std::size_t kBlock = 1024;  // fixed, so the sums do not depend on the threads
    parallelFor((count + kBlock - 1) / kBlock, threads, [&](std::size_t block) {
        const std::size_t first = block * kBlock, n = std::min(kBlock, count - first);
        std::vector<std::uint32_t> indices(n);
        for (std::size_t j = 0; j < n; ++j)
            indices[j] = static_cast<std::uint32_t>(texels.empty() ? first + j : texels[first + j]);
        LearnedDecoder::Pass pass;
        net.forward(codeValues(coefficients, scale, bias, indices), features, pass);
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t c = 0; c < C; ++c)
                out[(first + j) * C + c] =
                    std::clamp(pass.output(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(j)), 0.f, 1.f);
    });
    return out;
}

Image LearnedModel::render(Direction light) const {
    Image image(width, height, channels);
    image.samples = predict(light, {}, 0);
    return image;
}

std::optional<Result<LearnedOptions>> learnedModelNamed(const std::string& name) {
    constexpr std::string_view kind = "neural";
    if (name.compare(0, kind.size(), kind) != 0) return std::nullopt;
    const std::string digits = name.substr(kind.size());
    LearnedOptions o;
    if (digits.empty()) return Result<LearnedOptions>(o);
    int n = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    if (n < 1 || n > LearnedModel::kMaxCodes)
        return Result<LearnedOptions>(Error{"'" + name + "': a learned model has 1 to " +
                                            std::to_string(LearnedModel::kMaxCodes) + " codes per texel"});
    o.codes = n;
    return Result<LearnedOptions>(o);
}

std::string learnedModelName(const LearnedModel& model) { return "neural" + std::to_string(model.codes); }

}  // namespace btflut
