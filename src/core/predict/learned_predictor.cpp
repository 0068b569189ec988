#include "core/predict/learned_predictor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <utility>

#include "core/check.h"
#include "core/io/json_text.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_shader.h"

namespace btflut {

// Grey: one channel's codes (a grey model), or the sum of three.
LearnedPredictor::LearnedPredictor(LearnedModel model, bool perChannel)
    : Predictor(perChannel ? 3 : 1, perChannel || model.channels == 1 ? 255 : 765),
      m_model(std::move(model)),
      m_perChannel(perChannel) {
    BTFLUT_CHECK(!m_model.empty() && (!perChannel || m_model.channels == 3));
}

std::string LearnedPredictor::description() const {
    std::ostringstream out;
    out << name() << " (" << bytesPerTexel() << " bytes per texel; a linear basis of the codes and a ";
    const std::vector<int> sizes = m_model.decoderSizes();
    for (std::size_t k = 0; k < sizes.size(); ++k) out << (k ? "-" : "") << sizes[k];
    out << " residual network" << (m_model.residualConstant() ? " that adds a constant (the linear start kept)" : "")
        << ", " << m_model.decoderCost() << " multiply-adds per texel), relit per light"
        << (viewDependent() ? " and view" : "");
    return out.str();
}

std::string LearnedPredictor::beyondGpu() const {
    if (m_model.fitsGpu()) return {};
    return "its learned model (" + name() + ") has networks larger than the GPU's decoder evaluates (at most " +
           std::to_string(BTFLUT_LEARNED_HIDDEN) + " hidden layers of " + std::to_string(BTFLUT_LEARNED_WIDTH) +
           " units); it is relit on the CPU only (btflut relight, eval)";
}

// Its shader specialised to it (learned_shader.h): for neural9 on RGB (891 multiply-adds a
// texel) 5 flat pixels a relit texel and 8 a pixel per fragment, whose codes are sampled
// bilinearly (bench render --lut-path texture and fragment, dome-synth at 1920 x 1080, issue
// 46), in proportion to its size. The include's texture path, for networks past a shader's
// constants, costs ~40 times that (issue 35: 310 for 1107).
double LearnedPredictor::decodeCost(bool perFragment) const {
    if (!hasLearnedShader(m_model)) return 310.0 * static_cast<double>(m_model.decoderCost()) / 1107.0;
    return (perFragment ? 8.0 : 5.0) * static_cast<double>(multiplyAdds()) / 891.0;
}

// The codes four to a layer (as a light model's planes), and the decoder's texels.
PredictorPlanes LearnedPredictor::planes() const {
    const auto N = static_cast<std::size_t>(m_model.codes);
    PredictorPlanes out;
    out.scale = m_model.quantised.scale;
    out.bias = m_model.quantised.bias;
    for (std::size_t first = 0; first < N; first += 4) {
        Image layer(m_model.width, m_model.height, 4);
        for (std::size_t i = 0; i < m_model.texels(); ++i)
            for (std::size_t c = 0; c < 4 && first + c < N; ++c)
                layer.samples[i * 4 + c] = static_cast<float>(m_model.quantised.bytes[i * N + first + c]) / 255.f;
        out.layers.push_back(std::move(layer));
    }
    if (m_model.fitsGpu()) {
        LearnedModel::GpuNetwork network = m_model.gpuNetwork();
        out.network = std::move(network.texels);
        out.networkSize = network.size;
    }
    return out;
}

EngineParts LearnedPredictor::engineParts(const std::string& file) const {
    EngineParts out;
    out.planes = m_model.codes;
    out.channels = m_model.channels;
    out.weights = 4;  // the decoder in the weight texture: one layer, a square of texels
    out.shaderVersion = kShaderIncludeVersion;
    if (m_model.fitsGpu()) {
        LearnedModel::GpuNetwork network = m_model.gpuNetwork();
        out.weightGrid = std::move(network.texels);
        out.weightGridSize = network.size;
    }
    const LearnedShaderCost cost = learnedShaderCost(m_model);
    out.texelMultiplyAdds = cost.texelMultiplyAdds;
    out.frameMultiplyAdds = cost.frameMultiplyAdds;
    if (hasLearnedShader(m_model)) {
        out.networkGlsl = learnedShaderSource(m_model, ShaderLanguage::Glsl, file);
        out.networkHlsl = learnedShaderSource(m_model, ShaderLanguage::Hlsl, file);
    }
    return out;
}

std::vector<std::string> LearnedPredictor::shaderDefines() const {
    return {"PREDICT_LEARNED", "PREDICT_LEARNED_LAYERS " + std::to_string((m_model.codes + 3) / 4)};
}

std::size_t LearnedPredictor::multiplyAdds() const { return learnedShaderCost(m_model).texelMultiplyAdds; }

std::string LearnedPredictor::shaderSource() const {
    return hasLearnedShader(m_model) ? learnedShaderSource(m_model, ShaderLanguage::Glsl) : std::string();
}

// btflut.glsl's BtflutLearnedFrame: per layer of four codes and per channel ([layer * 3 +
// channel]) A_ck, the offsets a_c, the residual's first layer at the light.
std::vector<ShaderValues> LearnedPredictor::shaderValues(const PredictorFrame& frame) const {
    LearnedFrame& at = *frame.learned;
    std::call_once(at.uniformsOnce, [&] {
        const LearnedModel::LightFrame f = m_model.lightFrame(at.light, at.view);
        const auto N = static_cast<std::size_t>(m_model.codes), C = static_cast<std::size_t>(m_model.channels);
        std::vector<float> basis((N + 3) / 4 * 3 * 4, 0.f), offset(3, 0.f), hidden(BTFLUT_LEARNED_WIDTH, 0.f);
        for (std::size_t c = 0; c < C; ++c) {
            for (std::size_t k = 0; k < N; ++k) basis[((k / 4) * 3 + c) * 4 + k % 4] = f.basis[c * (N + 1) + k];
            offset[c] = f.basis[c * (N + 1) + N];
        }
        std::copy(f.hidden.begin(), f.hidden.end(), hidden.begin());
        at.uniforms = {{"predictLearned.basis", 4, std::move(basis)},
                       {"predictLearned.offset", 3, std::move(offset)},
                       {"predictLearned.hidden", 4, std::move(hidden)}};
    });
    return at.uniforms;
}

PredictorFrame LearnedPredictor::frameAt(Direction light, Direction view) const {
    PredictorFrame frame;
    frame.count = 0;
    frame.learned = std::make_shared<LearnedFrame>();
    frame.learned->light = light;
    frame.learned->view = view;
    return frame;
}

namespace {
std::uint8_t codeOfValue(float v) { return static_cast<std::uint8_t>(std::lround(v * 255.f)); }
}  // namespace

const std::uint8_t* LearnedPredictor::decoded(const PredictorFrame& frame, std::size_t texel) const {
    LearnedFrame& f = *frame.learned;
    std::call_once(f.once, [&] {
        const std::vector<float> values = m_model.predict(f.light, {}, 0, f.view);
        f.codes.resize(values.size());
        std::transform(values.begin(), values.end(), f.codes.begin(), codeOfValue);
    });
    return &f.codes[texel * static_cast<std::size_t>(m_model.channels)];
}

std::size_t LearnedPredictor::codeOf(const std::uint8_t* p, int channel) const {
    if (m_perChannel) return p[channel];
    return m_model.channels == 1 ? p[0] : std::size_t{p[0]} + p[1] + p[2];
}

std::size_t LearnedPredictor::code(const PredictorFrame& frame, std::size_t texel, int channel) const {
    return codeOf(decoded(frame, texel), channel);
}

void LearnedPredictor::colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const {
    const std::uint8_t* p = decoded(frame, texel);
    for (int c = 0; c < 3; ++c) rgb[c] = static_cast<float>(p[m_model.channels == 3 ? c : 0]) / 255.f;
}

// A sample of at most half the texels is decoded on its own (the match grid's nodes count
// their sample and never read a texel); a larger one reads the frame's decoding.
void LearnedPredictor::countCodes(const PredictorFrame& frame, std::span<const std::uint32_t> texels, int channel,
                                  std::vector<std::uint64_t>& counts) const {
    if (2 * texels.size() > m_model.texels()) {
        countCodesOf(*this, frame, texels, channel, counts);
        return;
    }
    const std::vector<float> values = m_model.predict(frame.learned->light, texels, 1, frame.learned->view);
    const auto C = static_cast<std::size_t>(m_model.channels);
    std::uint8_t p[3];
    for (std::size_t j = 0; j < texels.size(); ++j) {
        for (std::size_t c = 0; c < C; ++c) p[c] = codeOfValue(values[j * C + c]);
        ++counts[codeOf(p, channel) + 1];
    }
}

void LearnedPredictor::levelCodes(const PredictorFrame& frame, int level, int width, int height,
                                  std::span<const std::uint32_t> texels, std::vector<std::size_t>& codes) const {
    BTFLUT_CHECK(width == m_model.width && height == m_model.height);
    std::vector<float> values;
    if (level == 0) {
        values = m_model.predict(frame.learned->light, texels, 0, frame.learned->view);
    } else {
        const auto N = static_cast<std::size_t>(m_model.codes);
        std::vector<std::uint8_t> means(texels.size() * N);
        for (std::size_t j = 0; j < texels.size(); ++j)
            levelTexelBytes(m_model.quantised.bytes, width, height, m_model.codes, level, texels[j], &means[j * N]);
        values = m_model.predictCodes(frame.learned->light, std::move(means), 0, frame.learned->view);
    }
    const auto C = static_cast<std::size_t>(m_model.channels), matched = static_cast<std::size_t>(channels());
    codes.resize(texels.size() * matched);
    std::uint8_t p[3];
    for (std::size_t j = 0; j < texels.size(); ++j) {
        for (std::size_t c = 0; c < C; ++c) p[c] = codeOfValue(values[j * C + c]);
        for (std::size_t c = 0; c < matched; ++c) codes[j * matched + c] = codeOf(p, static_cast<int>(c));
    }
}

Bytes encodeLearnedModelChunk(const LearnedModel& m, std::uint32_t version) {
    BTFLUT_CHECK(version >= 9 || m.viewFeatures == 0);
    ByteWriter w;
    w.put(static_cast<std::uint32_t>(m.codes));
    w.put(static_cast<std::uint32_t>(m.channels));
    if (version >= 9) w.put(static_cast<std::uint32_t>(m.viewFeatures));
    for (const std::vector<int>* widths : {&m.lightHidden, &m.hidden}) {
        w.put(static_cast<std::uint32_t>(widths->size()));
        for (int h : *widths) w.put(static_cast<std::uint32_t>(h));
    }
    for (float v : m.quantised.scale) w.put(v);
    for (float v : m.quantised.bias) w.put(v);
    for (const Network* network : {&m.decoder->light, &m.decoder->residual}) {
        const std::vector<float> parameters = network->parameters();
        w.put(static_cast<std::uint32_t>(parameters.size()));
        w.putBytes(parameters.data(), parameters.size() * sizeof(float));
    }
    const auto N = static_cast<std::size_t>(m.codes);
    for (std::size_t first = 0; first < N; first += 3) {
        Image image(m.width, m.height, 3);
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3 && first + c < N; ++c)
                image.samples[i * 3 + c] = static_cast<float>(m.quantised.bytes[i * N + first + c]) / 255.f;
        putPng(w, image, 8);
    }
    return std::move(w.bytes());
}

Result<LearnedModel> decodeLearnedModelChunk(ByteReader& in, const ChunkSource& source, std::uint32_t version,
                                             int referenceChannels) {
    auto fail = [&](const std::string& what) { return source.fail(what); };
    LearnedModel m;
    const auto codes = in.get<std::uint32_t>(), channels = in.get<std::uint32_t>();
    if (!in.ok() || codes < 1 || codes > static_cast<std::uint32_t>(LearnedModel::kMaxCodes) ||
        (channels != 1 && channels != 3) || channels > static_cast<std::uint32_t>(referenceChannels))
        return fail("invalid description");
    m.codes = static_cast<int>(codes);
    m.channels = static_cast<int>(channels);
    if (version >= 9) {  // a model of views takes the view's features too
        const auto views = in.get<std::uint32_t>();
        if (!in.ok() || (views != 0 && views != static_cast<std::uint32_t>(kLearnedViewFeatures)))
            return fail("invalid view feature count");
        m.viewFeatures = static_cast<int>(views);
    }
    m.width = source.width;
    m.height = source.height;
    for (std::vector<int>* widths : {&m.lightHidden, &m.hidden}) {
        const auto layers = in.get<std::uint32_t>();
        if (!in.ok() || layers > 8 || (widths == &m.hidden && layers < 1)) return fail("invalid layer count");
        for (std::uint32_t k = 0; k < layers; ++k) {
            const auto width = in.get<std::uint32_t>();
            if (!in.ok() || width < 1 || width > 256) return fail("invalid hidden layer width");
            widths->push_back(static_cast<int>(width));
        }
    }
    QuantisedCodes& q = m.quantised;
    for (std::uint32_t k = 0; k < codes; ++k) q.scale.push_back(in.get<float>());
    for (std::uint32_t k = 0; k < codes; ++k) q.bias.push_back(in.get<float>());
    if (!in.ok()) return fail("truncated");
    for (std::uint32_t k = 0; k < codes; ++k)
        if (!std::isfinite(q.scale[k]) || !(q.scale[k] > 0) || !std::isfinite(q.bias[k]))
            return fail("invalid scale or bias");
    LearnedDecoder decoder;
    for (Network* network : {&decoder.light, &decoder.residual}) {
        const std::vector<int> sizes = network == &decoder.light ? m.lightSizes() : m.decoderSizes();
        const auto parameters = in.get<std::uint32_t>();
        const std::size_t expected = LearnedModel::parameterCount(sizes);
        if (!in.ok() || parameters != expected || expected > static_cast<std::size_t>(LearnedModel::kMaxParameters) ||
            parameters > in.remaining() / 4)
            return fail("a network's parameters do not fit its sizes");
        std::vector<float> values(parameters);
        if (const std::uint8_t* bytes = in.getBytes(parameters * sizeof(float)); bytes)
            std::memcpy(values.data(), bytes, parameters * sizeof(float));
        for (float v : values)
            if (!std::isfinite(v)) return fail("a network parameter is not finite");
        *network = Network::fromParameters(sizes, values);
    }
    m.decoder = std::make_shared<const LearnedDecoder>(std::move(decoder));
    const std::size_t N = codes;
    q.bytes.resize(m.texels() * N);
    for (std::size_t first = 0; first < N; first += 3) {
        const std::string what = "codes " + std::to_string(first) + "-" + std::to_string(std::min(N, first + 3) - 1);
        Result<Image> image = readRgb8Plane(in, source, what, source.name + " (learned " + what + ")");
        if (!image) return Error{image.error()};
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3 && first + c < N; ++c)
                q.bytes[i * N + first + c] = static_cast<std::uint8_t>(std::lround(image->samples[i * 3 + c] * 255));
    }
    if (in.remaining() != 0) return fail("has the wrong size");
    return m;
}

// The learned model's part: its networks and its codes' images (docs/predictors.md; its LRND
// chunk in docs/btflut-format.md).
void LearnedPredictor::atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const {
    const LearnedModel& m = m_model;
    nlohmann::json sidecar{{"codes", m.codes},
                           {"channels", m.channels},
                           {"scale", m.quantised.scale},
                           {"bias", m.quantised.bias},
                           {"light_network_sizes", m.lightSizes()},
                           {"light_network", m.decoder->light.parameters()},
                           {"residual_sizes", m.decoderSizes()},
                           {"residual", m.decoder->residual.parameters()},
                           {"images", atlasImages(planes().layers, "codes", texture)}};
    sidecar["layout"] =
        "images: the codes four to an image (R, G, B, A); value = (code - bias) * scale; each network: per "
        "layer its weights (an output's inputs together), then its biases, ELU between layers, the last "
        "linear; the light network of the light's 9 hsh terms of order 3 gives channel c's weight on code k "
        "(output c (codes + 1) + k) and its offset (output c (codes + 1) + codes); the residual network of the "
        "codes' values and the same terms adds to each channel";
    blend["learned"] = std::move(sidecar);
}

const KindChunk kLearnedModelChunk{
    .kind = PredictorKind::Learned,
    .number = 3,
    .tag = "LRND",
    .since = 8,
    .missing = "a bank predicted by a learned model without its model (LRND chunk), or of another colour",
    .version = [](const Predictor& p) -> std::uint32_t { return p.viewDependent() ? 9 : 8; },
    .encode =
        [](const Predictor& p, std::uint32_t version) {
            return encodeLearnedModelChunk(static_cast<const LearnedPredictor&>(p).model(), version);
        },
    .decode = [](ByteReader& in, const ChunkSource& source, std::uint32_t version, int referenceChannels,
                 bool perChannel, bool greyAndAlbedo) -> Result<std::shared_ptr<const Predictor>> {
        Result<LearnedModel> model = decodeLearnedModelChunk(in, source, version, referenceChannels);
        if (!model) return Error{model.error()};
        if (greyAndAlbedo || (perChannel && model->channels != 3)) return std::shared_ptr<const Predictor>();
        return std::shared_ptr<const Predictor>(std::make_shared<LearnedPredictor>(std::move(*model), perChannel));
    }};

// Its codes; its decoder's shader files and costs; the weight texture, its network read exactly.
void LearnedPredictor::materialFields(nlohmann::json& predictor, const EngineParts& parts) const {
    predictor["images_layout"] =
        "RGBA8, codes four to an image (code k: image k / 4, channel k % 4); value_k = (code_k - bias[k]) * "
        "scale[k], code 0 .. 255";
    if (!parts.networkGlsl.empty())
        predictor["network"] = {
            {"glsl", kNetworkFiles[0]},
            {"hlsl", kNetworkFiles[1]},
            {"godot", kNetworkFiles[2]},
            {"texel_multiply_adds", parts.texelMultiplyAdds},
            {"frame_multiply_adds", parts.frameMultiplyAdds},
            {"how",
             "the decoder specialised to this material, its weights as constants: include it after btflut.glsl "
             "(btflut.hlsl, btflut.gdshaderinc); per fragment btflutRelightPrediction(..., "
             "btflutNetworkPrediction(planes, uv, frame)) with the frame (BtflutLearnedFrame) of the light: "
             "btflutNetworkFrame(light, view) per fragment where the light varies over the surface (a point "
             "light, a curved mesh: frame_multiply_adds more a pixel), else once per light change as a uniform "
             "(the weights.bin network's light part, docs/engines.md)"}};
    predictor["weights"]["row"] =
        "the decoder network's parameters, texel t at (t % grid_size, t / grid_size) of the one layer (btflut.glsl: A "
        "learned model)";
    predictor["weights"]["grid_mapping"] = "none: read exactly with texelFetch";
}

std::string LearnedFit::settings() const {
    const LearnedOptions& o = m_options;
    std::string text = "learned " + std::to_string(o.codes) + " " + std::to_string(o.seed) + " " +
                       std::to_string(o.steps) + " " + std::to_string(o.seconds) + " hidden";
    for (int w : o.hidden) text += " " + std::to_string(w);
    return text;
}

const FitKind& LearnedFit::kind() const { return kLearnedFit; }

FitPointer LearnedFit::trainedFor(double seconds, std::function<void(double)> progress) const {
    LearnedOptions o = m_options;
    if (seconds > 0) o.seconds = seconds;
    o.progress = std::move(progress);
    return learnedFit(std::move(o));
}

namespace {
Result<LearnedModel> trainedLearnedModel(const LearnedOptions& options, const FitImages& in) {
    LearnedOptions o = options;
    o.threads = in.threads;
    return fitLearnedModel(in.images, in.lights, in.mask, o, in.what, in.views);
}
}  // namespace

Result<PredictorPointer> LearnedFit::fit(const FitImages& in) const {
    Result<LearnedModel> model = trainedLearnedModel(m_options, in);
    if (!model) return Error{model.error()};
    return PredictorPointer(std::make_shared<LearnedPredictor>(std::move(*model), in.perChannel));
}

Result<UnmatchedModel> LearnedFit::fitUnmatched(const FitImages& in) const {
    Result<LearnedModel> model = trainedLearnedModel(m_options, in);
    if (!model) return Error{model.error()};
    auto m = std::make_shared<LearnedModel>(std::move(*model));
    const auto multiplyAdds = static_cast<double>(learnedShaderCost(*m).texelMultiplyAdds);
    return UnmatchedModel{[m](Direction light, Direction view) { return m->render(light, view); },
                          static_cast<double>(m->codes), multiplyAdds};
}

FitPointer learnedFit(LearnedOptions options) { return std::make_shared<LearnedFit>(std::move(options)); }

const FitKind kLearnedFit{
    fitNamed<learnedModelNamed, learnedFit>, true, true, [](const CandidateBounds& bounds) {
        // Predicting colour itself: no albedo.
        const int codes = std::min(bounds.bytes, LearnedModel::kMaxCodes);
        if (codes < 1) return std::vector<FitCandidate>{};
        const LearnedOptions o{.codes = codes, .seconds = bounds.seconds};
        return std::vector<FitCandidate>{{"neural" + std::to_string(codes), learnedFit(o), codes,
                                          learnedTexelMultiplyAdds(codes, bounds.channels == 3 ? 3 : 1, o.hidden)}};
    }};

}  // namespace btflut
