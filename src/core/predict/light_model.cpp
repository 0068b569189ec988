#include "core/predict/light_model.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "core/check.h"

namespace btflut {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

const char* lightBasisName(LightBasis basis) {
    switch (basis) {
        case LightBasis::Ptm:
            return "ptm";
        case LightBasis::Hsh:
            return "hsh";
        case LightBasis::Rbf:
            return "rbf";
        case LightBasis::Bilinear:
            return "bln";
    }
    return "?";
}

Result<LightBasis> parseLightBasis(const std::string& name) {
    for (LightBasis b : {LightBasis::Ptm, LightBasis::Hsh, LightBasis::Rbf, LightBasis::Bilinear})
        if (name == lightBasisName(b)) return b;
    return Error{"unknown basis '" + name + "' (ptm, hsh, rbf or bln)"};
}

std::optional<Result<LightModelOptions>> lightModelNamed(const std::string& name) {
    if (name == "ptm") return Result<LightModelOptions>(LightModelOptions{.basis = LightBasis::Ptm});
    for (LightBasis b : {LightBasis::Hsh, LightBasis::Rbf, LightBasis::Bilinear}) {
        const std::string prefix = lightBasisName(b);
        if (name.rfind(prefix, 0) != 0) continue;
        std::string number = name.substr(prefix.size());
        LightModelOptions o{.basis = b, .order = 2, .planes = 9};
        if (b != LightBasis::Hsh && !number.empty() && number.back() == 'c') {
            o.packed = true;
            number.pop_back();
        }
        if (!number.empty()) {
            char* end = nullptr;
            const long n = std::strtol(number.c_str(), &end, 10);
            const bool hsh = b == LightBasis::Hsh;
            if (*end != '\0' || !(hsh ? n == 2 || n == 3 : n >= 1 && n <= LightModel::kMaxPlanes))
                return Result<LightModelOptions>(
                    Error{"'" + name + "': " +
                          (hsh ? std::string("hsh2 or hsh3 (the order)")
                               : prefix + "N with N planes from 1 to " + std::to_string(LightModel::kMaxPlanes))});
            (hsh ? o.order : o.planes) = static_cast<int>(n);
        }
        return Result<LightModelOptions>(o);
    }
    return std::nullopt;
}

std::string lightModelName(const LightModel& model) {
    const std::string name = lightBasisName(model.basis);
    if (model.basis == LightBasis::Ptm) return name;
    if (model.basis == LightBasis::Hsh) return name + std::to_string(model.order);
    if (model.wide < model.planes) return name + std::to_string(model.bytesPerTexel()) + "c";
    return name + std::to_string(model.planes);
}

int LightModel::termCount(LightBasis basis, int order) {
    if (basis == LightBasis::Ptm) return kPtmTerms;
    if (basis == LightBasis::Hsh) return order * order;
    return 0;
}

std::vector<double> basisTerms(LightBasis basis, int order, Direction light) {
    if (basis == LightBasis::Ptm) {
        const Vec3 l = toVector(light);
        return {l.x * l.x, l.y * l.y, l.x * l.y, l.x, l.y, 1.0};
    }
    BTFLUT_CHECK(basis == LightBasis::Hsh && (order == 2 || order == 3));
    // Hemispherical harmonics: spherical harmonics with cos(theta) remapped to 2 cos(theta) - 1,
    // orthonormal over the hemisphere (Gautron et al. 2004), real form.
    const double c = std::cos(light.theta), phi = light.phi;
    const double s = std::sqrt(std::max(0.0, c - c * c));  // sin of the remapped angle / 2
    std::vector<double> t{1 / std::sqrt(2 * kPi), std::sqrt(6 / kPi) * std::cos(phi) * s,
                          std::sqrt(3 / (2 * kPi)) * (2 * c - 1), std::sqrt(6 / kPi) * std::sin(phi) * s};
    if (order == 3) {
        t.push_back(std::sqrt(30 / kPi) * std::cos(2 * phi) * (c * c - c));
        t.push_back(std::sqrt(30 / kPi) * std::cos(phi) * (2 * c - 1) * s);
        t.push_back(std::sqrt(5 / (2 * kPi)) * (1 - 6 * c + 6 * c * c));
        t.push_back(std::sqrt(30 / kPi) * std::sin(phi) * (2 * c - 1) * s);
        t.push_back(std::sqrt(30 / kPi) * std::sin(2 * phi) * (c * c - c));
    }
    return t;
}

LightModel::Weights LightModel::weightsAt(Direction light) const {
    const auto P = static_cast<std::size_t>(planes), C = static_cast<std::size_t>(channels);
    Weights w;
    w.weight.assign(P * C, 0.f);
    if (basis == LightBasis::Ptm || basis == LightBasis::Hsh) {
        const std::vector<double> t = basisTerms(basis, order, light);
        for (std::size_t p = 0; p < P; ++p)
            for (std::size_t c = 0; c < C; ++c) w.weight[p * C + c] = static_cast<float>(t[p]);
        return w;
    }
    // Blend table rows (offset, then each plane's weights, per channel).
    const std::size_t row = (1 + P) * C;
    std::vector<double> sum(row, 0.0);
    auto add = [&](std::size_t index, double g) {
        const float* r = &table[index * row];
        for (std::size_t k = 0; k < row; ++k) sum[k] += g * r[k];
    };
    if (basis == LightBasis::Rbf) {
        const Vec3 l = toVector(light);
        std::vector<double> g(lights.size());
        double total = 0;
        for (std::size_t i = 0; i < lights.size(); ++i) {
            const Vec3 m = toVector(lights[i]);
            const double d2 = (l.x - m.x) * (l.x - m.x) + (l.y - m.y) * (l.y - m.y) + (l.z - m.z) * (l.z - m.z);
            g[i] = std::exp(-d2 / (double{sigma} * sigma));
            total += g[i];
        }
        if (!(total > 1e-300)) {  // far from every light for this sigma: the nearest alone
            std::size_t nearest = 0;
            for (std::size_t i = 1; i < lights.size(); ++i)
                if (angleBetween(lights[i], light) < angleBetween(lights[nearest], light)) nearest = i;
            add(nearest, 1);
        } else {
            for (std::size_t i = 0; i < lights.size(); ++i) add(i, g[i] / total);
        }
    } else {
        const GridCell cell = gridCellAt(toDisk(light), grid);
        for (std::size_t k = 0; k < 4; ++k) add(cell.node[k], cell.weight[k]);
    }
    for (std::size_t c = 0; c < C; ++c) w.offset[c] = static_cast<float>(sum[c]);
    for (std::size_t p = 0; p < P; ++p)
        for (std::size_t c = 0; c < C; ++c) w.weight[p * C + c] = static_cast<float>(sum[(1 + p) * C + c]);
    return w;
}

Image LightModel::render(Direction light) const {
    const Weights w = weightsAt(light);
    const auto P = static_cast<std::size_t>(planes), C = static_cast<std::size_t>(channels);
    const int outputs = albedo.empty() ? channels : 3;
    Image out(width, height, outputs);
    for (std::size_t i = 0; i < texels(); ++i) {
        std::array<double, 3> value{};
        for (std::size_t c = 0; c < C; ++c) {
            double v = w.offset[c];
            for (std::size_t p = 0; p < P; ++p)
                v += (coefficients[i * P + p] - double{bias[p]}) * scale[p] * w.weight[p * C + c];
            value[c] = v;
        }
        for (int c = 0; c < outputs; ++c) {
            const double a = albedo.empty() ? 1.0 : albedo[i * 3 + static_cast<std::size_t>(c)] / 255.0;
            const double v = value[C == 1 ? 0 : static_cast<std::size_t>(c)];
            out.samples[i * static_cast<std::size_t>(outputs) + static_cast<std::size_t>(c)] =
                static_cast<float>(std::clamp(a * v, 0.0, 1.0));
        }
    }
    return out;
}

namespace {

// A light's weights folded with each plane's scale and bias, so that a texel's value is
// S_c = O'_c + sum_p code_p W'_pc: W'_pc = scale_p w_pc [p * C + c], O'_c = o_c - sum_p bias_p W'_pc.
struct FoldedWeights {
    std::vector<double> weights;
    std::array<double, 3> offset{};
};

FoldedWeights foldedWeights(const LightModel& model, Direction light) {
    const LightModel::Weights w = model.weightsAt(light);
    const auto P = static_cast<std::size_t>(model.planes), C = static_cast<std::size_t>(model.channels);
    FoldedWeights f;
    f.weights.resize(P * C);
    for (std::size_t c = 0; c < C; ++c) {
        f.offset[c] = w.offset[c];
        for (std::size_t p = 0; p < P; ++p) {
            f.weights[p * C + c] = double{model.scale[p]} * w.weight[p * C + c];
            f.offset[c] -= double{model.bias[p]} * f.weights[p * C + c];
        }
    }
    return f;
}

}  // namespace

LightModelFixed lightModelFixed(const LightModel& model, Direction light) {
    const auto P = static_cast<std::size_t>(model.planes), C = static_cast<std::size_t>(model.channels);
    const FoldedWeights folded = foldedWeights(model, light);
    double bound = 0;  // the largest |S_c| (codes at most maxCode)
    for (std::size_t c = 0; c < C; ++c) {
        double sum = 0;
        for (std::size_t p = 0; p < P; ++p)
            sum += model.maxCode(static_cast<int>(p)) * std::abs(folded.weights[p * C + c]);
        bound = std::max(bound, std::abs(folded.offset[c]) + sum);
    }
    // The most fraction bits that keep |S_c| below 2^23 (exact in a float, fused or not).
    int shift = -40;
    while (shift < 40 && bound * std::ldexp(1.0, shift + 1) < 0x1p23) ++shift;
    // Clamped for models no capture makes (weights beyond 2^63 in a corrupt file): still integers.
    auto integer = [&](double v) {
        const double scaled = std::ldexp(v, shift);
        return static_cast<std::int32_t>(std::isfinite(scaled) ? std::clamp(std::round(scaled), -0x1p30, 0x1p30) : 0.0);
    };
    LightModelFixed f;
    f.weights.resize(P * C);
    for (std::size_t k = 0; k < P * C; ++k) f.weights[k] = integer(folded.weights[k]);
    for (std::size_t c = 0; c < C; ++c) f.offset[c] = integer(folded.offset[c]);
    static_assert(kWeightUnit == 4096, "the luminance is scaled to 2^12");
    f.scale = static_cast<float>(std::ldexp(1.0, 12 - shift));
    return f;
}

std::array<std::int64_t, 3> predictFixed(const LightModel& model, const LightModelFixed& fixed, std::size_t texel) {
    const auto P = static_cast<std::size_t>(model.planes), C = static_cast<std::size_t>(model.channels);
    const std::uint8_t* bytes = &model.coefficients[texel * P];
    std::array<std::int64_t, 3> value{};
    for (std::size_t c = 0; c < C; ++c) {
        std::int64_t sum = fixed.offset[c];
        for (std::size_t p = 0; p < P; ++p) sum += std::int64_t{bytes[p]} * fixed.weights[p * C + c];
        value[c] =
            static_cast<std::int64_t>(std::clamp(std::floor(static_cast<double>(sum) * fixed.scale), -0x1p40, 0x1p40));
    }
    std::array<std::int64_t, 3> out{};
    const std::size_t outputs = model.albedo.empty() ? C : 3;
    for (std::size_t c = 0; c < outputs; ++c) {
        const std::int64_t a = model.albedo.empty() ? 255 : model.albedo[texel * 3 + c];
        out[c] = std::clamp<std::int64_t>(a * value[C == 1 ? 0 : c], 0, 255 * kWeightUnit);
    }
    return out;
}

std::vector<Image> lightModelImages(const LightModel& m) {
    const auto P = static_cast<std::size_t>(m.planes), wide = static_cast<std::size_t>(m.wide);
    std::vector<Image> images;
    for (std::size_t first = 0; first < wide; first += 3) {
        Image image(m.width, m.height, 3);
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3 && first + c < wide; ++c)
                image.samples[i * 3 + c] = m.coefficients[i * P + first + c] / 255.f;
        images.push_back(std::move(image));
    }
    for (std::size_t first = wide; first < P; first += 6) {
        Image image(m.width, m.height, 3);
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3; ++c) {
                const std::size_t high = first + 2 * c, low = high + 1;
                const int code =
                    (high < P ? m.coefficients[i * P + high] : 0) * 16 + (low < P ? m.coefficients[i * P + low] : 0);
                image.samples[i * 3 + c] = static_cast<float>(code) / 255.f;
            }
        images.push_back(std::move(image));
    }
    if (!m.albedo.empty()) {
        Image image(m.width, m.height, 3);
        std::transform(m.albedo.begin(), m.albedo.end(), image.samples.begin(),
                       [](std::uint8_t b) { return b / 255.f; });
        images.push_back(std::move(image));
    }
    return images;
}

}  // namespace btflut
