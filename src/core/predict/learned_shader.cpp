#include "core/predict/learned_shader.h"

#include <cstdio>

#include "core/check.h"
#include "core/learn/network.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/learned_decoder.h"

namespace btflut {

namespace {

constexpr int kCodeLayers = BTFLUT_MAX_PLANES / 4;  // btflut.glsl's BTFLUT_MAX_LAYERS
constexpr int kFrameBasis = kCodeLayers * 3;        // BtflutLearnedFrame.basis
constexpr int kFrameHidden = BTFLUT_LEARNED_WIDTH / 4;

int groups(int values) { return (values + 3) / 4; }

// The two languages differ here only in names and in how a struct and an array start.
struct Syntax {
    ShaderLanguage language;
    bool hlsl() const { return language == ShaderLanguage::Hlsl; }
    const char* vec3() const { return hlsl() ? "float3" : "vec3"; }
    const char* vec4() const { return hlsl() ? "float4" : "vec4"; }
    const char* vec2() const { return hlsl() ? "float2" : "vec2"; }
};

// A float as a literal both languages read as float (GLSL ES converts no int), exactly: 9
// significant digits give the float back.
std::string literal(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", static_cast<double>(v));
    std::string s = text;
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    return s;
}

std::string vec4Literal(const Syntax& s, const float (&v)[4]) {
    return std::string(s.vec4()) + "(" + literal(v[0]) + ", " + literal(v[1]) + ", " + literal(v[2]) + ", " +
           literal(v[3]) + ")";
}

const char* component(int k) { return &"xyzw"[k]; }
std::string componentOf(const std::string& vector, int k) { return vector + "." + std::string(1, "xyzw"[k]); }

// One fully connected layer, unrolled: output group j (four outputs) starts at start[j] and adds
// each input times its column of the group's weights (input i: column firstColumn + i of `w`),
// one vec4 multiply-add each, all-zero columns left out; then the ELU when `hidden`. Writes
// `name_j` and returns the outputs as scalar expressions. `constants` counts the literals.
std::vector<std::string> emitLayer(std::string& out, const Syntax& s, const std::string& name,
                                   const std::vector<std::string>& inputs, const Matrix& w, Eigen::Index firstColumn,
                                   const std::vector<std::string>& start, bool hidden, std::size_t& constants) {
    const auto outputs = static_cast<int>(w.rows());
    std::vector<std::string> result;
    for (int j = 0; j < groups(outputs); ++j) {
        const std::string group = name + "_" + std::to_string(j);
        out += "    " + std::string(s.vec4()) + " " + group + " = " + start[static_cast<std::size_t>(j)] + ";\n";
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            float column[4] = {0, 0, 0, 0};
            bool any = false;
            for (int k = 0; k < 4 && 4 * j + k < outputs; ++k) {
                column[k] = w(4 * j + k, firstColumn + static_cast<Eigen::Index>(i));
                any = any || column[k] != 0.f;
            }
            if (!any) continue;
            out += "    " + group + " += " + inputs[i] + " * " + vec4Literal(s, column) + ";\n";
            ++constants;
        }
        if (hidden) out += "    " + group + " = max(" + group + ", 0.0) + exp(min(" + group + ", 0.0)) - 1.0;\n";
        for (int k = 0; k < 4 && 4 * j + k < outputs; ++k) result.push_back(componentOf(group, k));
    }
    return result;
}

// A layer's biases as vec4 literals, one per group of four outputs.
std::vector<std::string> biasLiterals(const Syntax& s, const Vector& bias, std::size_t& constants) {
    std::vector<std::string> out;
    for (int j = 0; j < groups(static_cast<int>(bias.size())); ++j) {
        float v[4] = {0, 0, 0, 0};
        for (int k = 0; k < 4 && 4 * j + k < bias.size(); ++k) v[k] = bias(4 * j + k);
        out.push_back(vec4Literal(s, v));
        ++constants;
    }
    return out;
}

// The codes' values v_k = (byte_k - bias_k) scale_k, four to a vec4: v0, v1, ...
std::vector<std::string> emitCodeValues(std::string& out, const Syntax& s, const LearnedModel& m,
                                        std::size_t& constants) {
    std::vector<std::string> values;
    for (int l = 0; l < groups(m.codes); ++l) {
        float bias[4] = {0, 0, 0, 0}, scale[4] = {0, 0, 0, 0};
        for (int k = 0; k < 4 && 4 * l + k < m.codes; ++k) {
            bias[k] = m.quantised.bias[static_cast<std::size_t>(4 * l + k)];
            scale[k] = m.quantised.scale[static_cast<std::size_t>(4 * l + k)];
        }
        const std::string v = "v" + std::to_string(l);
        out += "    " + std::string(s.vec4()) + " " + v + " = (codes[" + std::to_string(l) + "] - " +
               vec4Literal(s, bias) + ") * " + vec4Literal(s, scale) + ";\n";
        constants += 2;
        for (int k = 0; k < 4 && 4 * l + k < m.codes; ++k) values.push_back(componentOf(v, k));
    }
    return values;
}

// btflutNetworkValue: the codes' linear basis at the frame, and the residual network from its
// first layer's light part (the frame's `hidden`).
void emitValue(std::string& out, const Syntax& s, const LearnedModel& m, std::size_t& constants) {
    const Network& residual = m.decoder->residual;
    out += std::string(s.vec3()) + " btflutNetworkValue(" + s.vec4() + " codes[" + std::to_string(kCodeLayers) +
           "], BtflutLearnedFrame f) {\n";
    const std::vector<std::string> v = emitCodeValues(out, s, m, constants);
    out += "    " + std::string(s.vec3()) + " value = f.offset;\n";
    for (int c = 0; c < m.channels; ++c) {
        out += "    value." + std::string(component(c), 1) + " +=";
        for (int l = 0; l < groups(m.codes); ++l)
            out += std::string(l ? " +" : "") + " dot(f.basis[" + std::to_string(l * 3 + c) + "], v" +
                   std::to_string(l) + ")";
        out += ";\n";
    }
    std::vector<std::string> x = v;
    const bool constant = m.residualConstant();
    if (constant) {  // its last layer's bias alone (the linear start)
        x.clear();
        const Vector& bias = residual.bias(residual.layers() - 1);
        for (int c = 0; c < m.channels; ++c) x.push_back(literal(bias(c)));
    }
    for (std::size_t layer = 0; layer < (constant ? 0 : residual.layers()); ++layer) {
        const bool last = layer + 1 == residual.layers();
        std::vector<std::string> start;
        if (layer == 0)
            for (int j = 0; j < groups(residual.sizes()[1]); ++j)
                start.push_back("f.hidden[" + std::to_string(j) + "]");
        else
            start = biasLiterals(s, residual.bias(layer), constants);
        x = emitLayer(out, s, "h" + std::to_string(layer + 1), x, residual.weights(layer), 0, start, !last, constants);
    }
    if (m.channels == 3) {
        out += "    value += " + std::string(s.vec3()) + "(" + x[0] + ", " + x[1] + ", " + x[2] + ");\n";
        out += "    return clamp(value, 0.0, 1.0);\n}\n\n";
    } else {
        out += "    value.x += " + x[0] + ";\n    return clamp(value.xxx, 0.0, 1.0);\n}\n\n";
    }
}

// btflutNetworkFrame: the light's (and view's) features, the light network, and the residual's
// first layer at codes 0 (its light part and bias), as LearnedModel::lightFrame.
void emitFrame(std::string& out, const Syntax& s, const LearnedModel& m, std::size_t& constants) {
    const Network &light = m.decoder->light, &residual = m.decoder->residual;
    const std::string arrayStart = s.hlsl() ? " = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}" : "";
    out += "BtflutLearnedFrame btflutNetworkFrame(" + std::string(s.vec3()) + " lightTangent, " + s.vec3() +
           " viewTangent) {\n";
    out += "    float t[9]" + arrayStart + ";\n";
    out += "    btflutBasisTerms(" + std::to_string(BTFLUT_BASIS_HSH) + ", lightTangent, t);\n";
    std::vector<std::string> h;
    for (int k = 0; k < kLearnedLightFeatures; ++k) h.push_back("t[" + std::to_string(k) + "]");
    if (m.viewFeatures > 0) {  // the view's order-2 terms but the constant (LearnedModel::featuresAt)
        out += "    float u[9]" + arrayStart + ";\n";
        out += "    btflutBasisTerms(" + std::to_string(BTFLUT_BASIS_HSH) + ", viewTangent, u);\n";
        for (int k = 0; k < m.viewFeatures; ++k) h.push_back("u[" + std::to_string(1 + k) + "]");
    }
    if (s.hlsl()) {
        out += "    BtflutLearnedFrame f = (BtflutLearnedFrame)0;\n";
    } else {
        out += "    BtflutLearnedFrame f;\n";
        out += "    for (int k = 0; k < " + std::to_string(kFrameBasis) + "; ++k) f.basis[k] = vec4(0.0);\n";
        out += "    for (int k = 0; k < " + std::to_string(kFrameHidden) + "; ++k) f.hidden[k] = vec4(0.0);\n";
        out += "    f.offset = vec3(0.0);\n";
    }
    std::vector<std::string> x = h;
    for (std::size_t layer = 0; layer < light.layers(); ++layer) {
        const bool last = layer + 1 == light.layers();
        x = emitLayer(out, s, "g" + std::to_string(layer + 1), x, light.weights(layer), 0,
                      biasLiterals(s, light.bias(layer), constants), !last, constants);
    }
    // Row c (N + 1) + k: A_ck, into basis[(k / 4) * 3 + c] component k % 4; row c (N + 1) + N: a_c.
    for (int c = 0; c < m.channels; ++c)
        for (int k = 0; k <= m.codes; ++k) {
            const std::string& row = x[static_cast<std::size_t>(c * (m.codes + 1) + k)];
            if (k == m.codes)
                out += "    f.offset." + std::string(component(c), 1) + " = " + row + ";\n";
            else
                out += "    f.basis[" + std::to_string((k / 4) * 3 + c) + "]." + std::string(component(k % 4), 1) +
                       " = " + row + ";\n";
        }
    if (!m.residualConstant()) {  // else btflutNetworkValue reads no hidden
        const std::vector<std::string> first =
            emitLayer(out, s, "a", h, residual.weights(0), m.codes, biasLiterals(s, residual.bias(0), constants), false,
                      constants);
        for (int j = 0; j < groups(static_cast<int>(first.size())); ++j)
            out += "    f.hidden[" + std::to_string(j) + "] = a_" + std::to_string(j) + ";\n";
    }
    out += "    return f;\n}\n\n";
}

// btflutNetworkPrediction: the planes' codes at uv (filtered, as btflutPrediction reads them),
// decoded and rounded to codes as btflutLearnedPrediction.
void emitPrediction(std::string& out, const Syntax& s, const LearnedModel& m) {
    out += "BtflutPrediction btflutNetworkPrediction(";
    out += s.hlsl() ? "Texture2DArray<float4> planes, SamplerState planesSampler" : "sampler2DArray planes";
    out += ", " + std::string(s.vec2()) + " uv, BtflutLearnedFrame f) {\n";
    out += "    " + std::string(s.vec4()) + " codes[" + std::to_string(kCodeLayers) + "];\n";
    for (int l = 0; l < kCodeLayers; ++l) {
        const std::string layer = std::to_string(l) + ".0";
        out += "    codes[" + std::to_string(l) + "] = ";
        if (l >= groups(m.codes))
            out += std::string(s.vec4()) + "(0.0, 0.0, 0.0, 0.0);\n";
        else if (s.hlsl())
            out += "planes.Sample(planesSampler, float3(uv, " + layer + ")) * 255.0;\n";
        else
            out += "texture(planes, vec3(uv, " + layer + ")) * 255.0;\n";
    }
    out += "    return btflutLearnedPredictionOf(btflutNetworkValue(codes, f));\n}\n";
}

}  // namespace

std::size_t learnedTexelMultiplyAdds(int codes, int channels, const std::vector<int>& hidden) {
    std::vector<int> sizes{codes};  // the codes' inputs alone: the light's are the frame's
    sizes.insert(sizes.end(), hidden.begin(), hidden.end());
    sizes.push_back(channels);
    std::size_t n = static_cast<std::size_t>(codes) * static_cast<std::size_t>(channels);
    for (std::size_t k = 0; k + 1 < sizes.size(); ++k)
        n += static_cast<std::size_t>(sizes[k]) * static_cast<std::size_t>(sizes[k + 1]);
    return n;
}

LearnedShaderCost learnedShaderCost(const LearnedModel& m) {
    BTFLUT_CHECK(!m.empty());
    LearnedShaderCost cost;
    const std::vector<int> sizes = m.decoderSizes(), light = m.lightSizes();
    const auto N = static_cast<std::size_t>(m.codes), F = static_cast<std::size_t>(m.features());
    if (m.residualConstant()) {  // the codes' basis alone
        cost.texelMultiplyAdds = N * static_cast<std::size_t>(m.channels);
        cost.constants = 2 * static_cast<std::size_t>(groups(m.codes));
    } else {
        cost.texelMultiplyAdds = learnedTexelMultiplyAdds(m.codes, m.channels, m.hidden);
        cost.frameMultiplyAdds = F * static_cast<std::size_t>(sizes[1]);
        cost.constants = 2 * static_cast<std::size_t>(groups(m.codes)) + N * static_cast<std::size_t>(groups(sizes[1]));
        for (std::size_t k = 1; k + 1 < sizes.size(); ++k)
            cost.constants += static_cast<std::size_t>(sizes[k] + 1) * static_cast<std::size_t>(groups(sizes[k + 1]));
    }
    for (std::size_t k = 0; k + 1 < light.size(); ++k)
        cost.frameMultiplyAdds += static_cast<std::size_t>(light[k]) * static_cast<std::size_t>(light[k + 1]);
    return cost;
}

bool hasLearnedShader(const LearnedModel& m) {
    return !m.empty() && m.decoderSizes()[1] <= BTFLUT_LEARNED_WIDTH &&
           learnedShaderCost(m).constants <= kMaxShaderConstants;
}

std::string learnedShaderSource(const LearnedModel& m, ShaderLanguage language, const std::string& name) {
    BTFLUT_CHECK(hasLearnedShader(m));
    const Syntax s{language};
    const LearnedShaderCost cost = learnedShaderCost(m);
    std::string out;
    out += "// The decoder of " + (name.empty() ? learnedModelName(m) : name) +
           " specialised to it (btflut's src/core/predict/learned_shader.h), generated: its weights as constants, "
           "its layers unrolled.\n";
    out += "// After the include (" + std::string(s.hlsl() ? "btflut.hlsl" : "btflut.glsl") + "). " +
           std::to_string(cost.texelMultiplyAdds) + " multiply-adds a texel; the frame " +
           std::to_string(cost.frameMultiplyAdds) + " more where it is " + "computed per fragment.\n";
    out += "#define BTFLUT_NETWORK 1\n";
    out += "#define BTFLUT_NETWORK_CODES " + std::to_string(m.codes) + "\n";
    out += "#define BTFLUT_NETWORK_CHANNELS " + std::to_string(m.channels) + "\n\n";
    std::size_t constants = 0;
    emitValue(out, s, m, constants);
    std::size_t frameConstants = 0;
    emitFrame(out, s, m, frameConstants);
    emitPrediction(out, s, m);
    BTFLUT_CHECK(constants <= cost.constants);
    return out;
}

}  // namespace btflut
