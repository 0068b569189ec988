#include "core/predict/rti_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

#include "core/check.h"

namespace btflut {

Bytes encodeHshRtiFile(const LightModel& model) {
    BTFLUT_CHECK(model.basis == LightBasis::Hsh && model.planes == model.order * model.order);
    static_assert(std::endian::native == std::endian::little, "the file's floats are little-endian");
    const std::size_t texels = model.texels(), terms = static_cast<std::size_t>(model.planes);
    // Each band's coefficients: the planes' values (HSH weighs them alike in every channel),
    // times the LRGB albedo where the model has one.
    auto coefficient = [&](std::size_t texel, std::size_t band, std::size_t term) {
        const double value = (model.coefficients[texel * terms + term] - double{model.bias[term]}) * model.scale[term];
        return model.albedo.empty() ? value : value * model.albedo[texel * 3 + band] / 255.0;
    };
    std::vector<float> low(terms, INFINITY), high(terms, -INFINITY);
    for (std::size_t t = 0; t < texels; ++t)
        for (std::size_t b = 0; b < 3; ++b)
            for (std::size_t q = 0; q < terms; ++q) {
                const auto v = static_cast<float>(coefficient(t, b, q));
                low[q] = std::min(low[q], v), high[q] = std::max(high[q], v);
            }
    std::vector<float> scale(terms), bias(low);
    for (std::size_t q = 0; q < terms; ++q) scale[q] = high[q] > low[q] ? high[q] - low[q] : 1.f;
    const std::string header = "#HSH1.2\n# written by btflut export --rti (hemispherical harmonics, order " +
                               std::to_string(model.order) + ")\n3\n" + std::to_string(model.width) + " " +
                               std::to_string(model.height) + " 3\n" + std::to_string(terms) + " 2 1\n";
    const std::size_t floats = header.size();
    Bytes out(floats + 2 * terms * sizeof(float) + texels * 3 * terms);
    std::memcpy(out.data(), header.data(), floats);
    std::memcpy(out.data() + floats, scale.data(), terms * sizeof(float));
    std::memcpy(out.data() + floats + terms * sizeof(float), bias.data(), terms * sizeof(float));
    std::uint8_t* bytes = out.data() + floats + 2 * terms * sizeof(float);
    for (std::size_t t = 0; t < texels; ++t)  // the model's rows are top first, as the file's
        for (std::size_t b = 0; b < 3; ++b)
            for (std::size_t q = 0; q < terms; ++q)
                *bytes++ = static_cast<std::uint8_t>(
                    std::clamp(std::lround((coefficient(t, b, q) - bias[q]) / scale[q] * 255.0), 0L, 255L));
    return out;
}

}  // namespace btflut
