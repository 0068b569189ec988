#include "core/predict/model_predictor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/check.h"
#include "core/io/json_text.h"

namespace btflut {

// Grey: one channel's codes (a grey model without albedo), or the sum of three.
ModelPredictor::ModelPredictor(LightModel model, bool perChannel)
    : Predictor(perChannel ? 3 : 1, perChannel || (model.albedo.empty() && model.channels == 1) ? 255 : 765),
      m_model(std::move(model)) {
    BTFLUT_CHECK(!m_model.empty());
}

std::string ModelPredictor::description() const {
    std::ostringstream out;
    out << name() << " (" << bytesPerTexel() << " bytes per texel), relit per light";
    return out.str();
}

PredictorPlanes ModelPredictor::planes() const {
    const LightModel& m = m_model;
    const auto P = static_cast<std::size_t>(m.planes);
    PredictorPlanes out;
    // 4-bit codes n are stored as 17 n (0 .. 255): value = (n - b) s = (17 n - 17 b) s / 17.
    auto widen = [&](std::size_t p) { return m.maxCode(static_cast<int>(p)) == 255 ? 1 : 17; };
    for (std::size_t p = 0; p < P; ++p) {
        out.scale.push_back(m.scale[p] / static_cast<float>(widen(p)));
        out.bias.push_back(m.bias[p] * static_cast<float>(widen(p)));
    }
    for (std::size_t first = 0; first < P; first += 4) {
        Image layer(m.width, m.height, 4);
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 4 && first + c < P; ++c)
                layer.samples[i * 4 + c] =
                    static_cast<float>(m.coefficients[i * P + first + c] * widen(first + c)) / 255.f;
        out.layers.push_back(std::move(layer));
    }
    if (!m.albedo.empty()) {
        out.albedo = Image(m.width, m.height, 3);
        std::transform(m.albedo.begin(), m.albedo.end(), out.albedo.samples.begin(),
                       [](std::uint8_t b) { return b / 255.f; });
    }
    return out;
}

std::vector<std::string> ModelPredictor::shaderDefines() const {
    const std::string layers = std::to_string((m_model.planes + 3) / 4);
    std::vector<std::string> d{"PREDICT_MODEL", "PREDICT_MODEL_LAYERS " + layers,
                               "PREDICT_MODEL_WIDE " + std::to_string(m_model.wide),
                               "PREDICT_MODEL_CHANNELS " + std::to_string(m_model.channels)};
    if (!m_model.albedo.empty()) d.insert(d.end(), {"PREDICT_MODEL_ALBEDO", "PREDICT_ALBEDO_LAYER " + layers});
    return d;
}

std::vector<ShaderValues> ModelPredictor::shaderValues(const PredictorFrame& frame) const {
    // btflut.glsl's BtflutModelFrame: per layer of four planes and per channel ([layer * 3 +
    // channel]) the planes' weights, the offsets, the scale (LightModelFixed; the CPU's twin:
    // predictFixed).
    const auto P = static_cast<std::size_t>(m_model.planes), C = static_cast<std::size_t>(m_model.channels);
    std::vector<float> weights((P + 3) / 4 * 3 * 4, 0.f);
    for (std::size_t q = 0; q < P; ++q)
        for (std::size_t c = 0; c < C; ++c)
            weights[((q / 4) * 3 + c) * 4 + q % 4] = static_cast<float>(frame.model.weights[q * C + c]);
    const LightModelFixed& f = frame.model;
    return {{"predictModel.weights", 4, std::move(weights)},
            {"predictModel.offset",
             3,
             {static_cast<float>(f.offset[0]), static_cast<float>(f.offset[1]), static_cast<float>(f.offset[2])}},
            {"predictModel.scale", 1, {f.scale}}};
}

PredictorFrame ModelPredictor::frameAt(Direction light, Direction /*view: one camera*/) const {
    PredictorFrame frame;
    frame.count = 0;
    frame.model = lightModelFixed(m_model, light);
    return frame;
}

std::size_t ModelPredictor::code(const PredictorFrame& frame, std::size_t texel, int channel) const {
    const std::array<std::int64_t, 3> c = predictFixed(m_model, frame.model, texel);
    return roundedCode(channels() == 3 ? c[static_cast<std::size_t>(channel)] : c[0] + c[1] + c[2], codes());
}

void ModelPredictor::colour(const PredictorFrame& frame, std::size_t texel, float* rgb) const {
    const std::array<std::int64_t, 3> c = predictFixed(m_model, frame.model, texel);
    for (std::size_t k = 0; k < 3; ++k) rgb[k] = static_cast<float>(c[k]) / (255.f * kWeightUnit);
}

namespace {

// A light model's rows ((1 + P) x channels: the offsets, then each plane's channel weights)
// over the engine's weight grid: bln's own nodes (its bilinear read is exact), rbf sampled.
std::vector<float> modelWeightGrid(const LightModel& m, int& size) {
    if (m.basis == LightBasis::Bilinear) {
        size = m.grid;
        return m.table;
    }
    size = kEngineWeightGrid;
    const auto P = static_cast<std::size_t>(m.planes), C = static_cast<std::size_t>(m.channels), row = (1 + P) * C;
    std::vector<float> grid(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * row);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const LightModel::Weights w =
                m.weightsAt(fromDisk(diskGridPoint(i, j, size)));  // beyond the rim: the horizon's
            float* node =
                &grid[(static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)) *
                      row];
            std::copy_n(w.offset.begin(), C, node);
            std::copy(w.weight.begin(), w.weight.end(), node + C);
        }
    return grid;
}

}  // namespace

EngineParts ModelPredictor::engineParts(const std::string&) const {
    const LightModel& m = m_model;
    EngineParts out;
    out.basis = m.basis;
    out.order = m.order;
    out.planes = m.planes;
    out.channels = m.channels;
    out.albedoMultiplies = !m.albedo.empty();
    if (m.basis == LightBasis::Rbf || m.basis == LightBasis::Bilinear) {
        out.weights = (m.planes + 1) * m.channels;
        const std::vector<float> rows = modelWeightGrid(m, out.weightGridSize);
        out.weightGrid = weightsInLayers(rows, static_cast<std::size_t>(out.weights), out.weightGridSize);
    }
    return out;
}

Bytes encodeLightModelChunk(const LightModel& m) {
    ByteWriter w;
    const std::array<std::uint32_t, 7> description{
        static_cast<std::uint32_t>(m.basis), static_cast<std::uint32_t>(m.planes),
        static_cast<std::uint32_t>(m.wide),  static_cast<std::uint32_t>(m.channels),
        static_cast<std::uint32_t>(m.order), m.albedo.empty() ? 0u : 1u,
        static_cast<std::uint32_t>(m.grid)};
    w.putBytes(description.data(), sizeof description);
    w.put(m.sigma);
    for (float v : m.scale) w.put(v);
    for (float v : m.bias) w.put(v);
    w.put(static_cast<std::uint32_t>(m.lights.size()));
    for (Direction d : m.lights) w.putDirection(d);
    w.put(static_cast<std::uint32_t>(m.table.size()));
    w.putBytes(m.table.data(), m.table.size() * sizeof(float));
    for (const Image& image : lightModelImages(m)) putPng(w, image, 8);  // the planes, then the albedo
    return std::move(w.bytes());
}

Result<LightModel> decodeLightModelChunk(ByteReader& in, const ChunkSource& source, int referenceChannels) {
    auto fail = [&](const std::string& what) { return source.fail(what); };
    const auto refChannels = static_cast<std::uint32_t>(referenceChannels);
    LightModel m;
    const auto basis = in.get<std::uint32_t>(), planes = in.get<std::uint32_t>(), wide = in.get<std::uint32_t>(),
               channels = in.get<std::uint32_t>(), order = in.get<std::uint32_t>(), albedo = in.get<std::uint32_t>(),
               grid = in.get<std::uint32_t>();
    m.sigma = in.get<float>();
    if (!in.ok()) return fail("truncated");
    if (basis > 3 || planes < 1 || planes > static_cast<std::uint32_t>(LightModel::kMaxPlanes) || wide > planes ||
        (channels != 1 && channels != 3) || albedo > 1)
        return fail("invalid description");
    m.wide = static_cast<int>(wide);
    m.basis = static_cast<LightBasis>(basis);
    m.planes = static_cast<int>(planes);
    m.channels = static_cast<int>(channels);
    m.order = static_cast<int>(order);
    m.width = source.width;
    m.height = source.height;
    const bool fixedBasis = m.basis == LightBasis::Ptm || m.basis == LightBasis::Hsh;
    if (fixedBasis &&
        (channels != 1 || (m.basis == LightBasis::Hsh ? order != 2 && order != 3 : order != 0) ||
         static_cast<int>(planes) != LightModel::termCount(m.basis, m.order) || grid != 0 || wide != planes))
        return fail("a " + std::string(lightBasisName(m.basis)) + " model with the wrong terms");
    // An albedo on a grey reference too: a bank's PTM (fitted with an albedo on grey images as
    // on colour ones) was the predictor of files before LMDL, and is written back as this.
    if (albedo ? refChannels != 3 && refChannels != 1 : channels != refChannels)
        return fail("its colour does not match the reference image's");
    if (m.basis == LightBasis::Bilinear && (grid < 2 || grid > 64)) return fail("invalid grid size");
    if (m.basis != LightBasis::Bilinear && grid != 0) return fail("a grid for a basis without one");
    m.grid = static_cast<int>(grid);
    if (m.basis == LightBasis::Rbf && !(std::isfinite(m.sigma) && m.sigma > 0)) return fail("invalid rbf width");
    for (std::uint32_t p = 0; p < planes; ++p) m.scale.push_back(in.get<float>());
    for (std::uint32_t p = 0; p < planes; ++p) m.bias.push_back(in.get<float>());
    for (std::uint32_t p = 0; p < planes; ++p)
        if (!std::isfinite(m.scale[p]) || !(m.scale[p] > 0) || !std::isfinite(m.bias[p]))
            return fail("invalid scale or bias");
    const auto lights = in.get<std::uint32_t>();
    if (!in.ok() || lights > in.remaining() / 16 || (m.basis == LightBasis::Rbf) != (lights > 0))
        return fail("invalid light count");
    for (std::uint32_t l = 0; l < lights; ++l) {
        Result<Direction> light = in.getDirection(source.name, "light model light");
        if (!light) return Error{light.error()};
        m.lights.push_back(*light);
    }
    const std::uint64_t row = (1 + std::uint64_t{planes}) * channels;
    const std::uint64_t rows = m.basis == LightBasis::Rbf        ? lights
                               : m.basis == LightBasis::Bilinear ? std::uint64_t{grid} * grid
                                                                 : 0;
    const auto tableLength = in.get<std::uint32_t>();
    if (!in.ok() || tableLength != rows * row || tableLength > in.remaining() / 4)
        return fail("the table does not fit the model");
    m.table.resize(tableLength);
    if (const std::uint8_t* bytes = in.getBytes(tableLength * sizeof(float)); bytes && tableLength > 0)
        std::memcpy(m.table.data(), bytes, tableLength * sizeof(float));
    for (float v : m.table)
        if (!std::isfinite(v)) return fail("a table value is not finite");
    m.albedo.resize(albedo ? m.texels() * 3 : 0);
    if (Status s = readModelPlanes(in, source, source.name + " (light model ", "planes ", m); !s)
        return Error{s.error()};
    if (in.remaining() != 0) return fail("has the wrong size");
    return m;
}

// The light model's part: its description, table and planes (docs/predictors.md; its LMDL chunk in
// docs/btflut-format.md).
void ModelPredictor::atlasSidecar(nlohmann::json& blend, const TextureWriter& texture) const {
    const LightModel& m = m_model;
    nlohmann::json sidecar{{"basis", lightBasisName(m.basis)},
                           {"name", lightModelName(m)},
                           {"planes", m.planes},
                           {"planes_8bit", m.wide},
                           {"channels", m.channels},
                           {"order", m.order},
                           {"scale", m.scale},
                           {"bias", m.bias},
                           {"images", atlasImages(lightModelImages(m), "model", texture)}};
    if (m.basis == LightBasis::Rbf) {
        sidecar["sigma"] = m.sigma;
        for (Direction d : m.lights) sidecar["lights"].push_back(directionJson(d));
    }
    if (m.basis == LightBasis::Bilinear) sidecar["grid"] = m.grid;
    if (!m.table.empty()) sidecar["table"] = m.table;
    sidecar["layout"] =
        "images: the 8-bit planes three to an image (R, G, B), then the 4-bit planes six to an image (two to a "
        "channel, the first in the high nibble), then the albedo if the model has one; value = (code - bias) * "
        "scale; table rows (per rbf light or bln grid node j * grid + i): the channels' offsets, then each "
        "plane's channel weights";
    blend["model"] = std::move(sidecar);
}

const KindChunk kLightModelChunk{
    .kind = PredictorKind::Model,
    .number = 2,
    .tag = "LMDL",
    .since = 5,
    .missing = "a bank predicted by a light model without its model (LMDL chunk)",
    .version = [](const Predictor&) -> std::uint32_t { return 5; },
    .encode = [](const Predictor& p,
                 std::uint32_t) { return encodeLightModelChunk(static_cast<const ModelPredictor&>(p).model()); },
    .decode = [](ByteReader& in, const ChunkSource& source, std::uint32_t, int referenceChannels, bool perChannel,
                 bool greyAndAlbedo) -> Result<std::shared_ptr<const Predictor>> {
        Result<LightModel> model = decodeLightModelChunk(in, source, referenceChannels);
        if (!model) return Error{model.error()};
        if (greyAndAlbedo) return std::shared_ptr<const Predictor>();
        return std::shared_ptr<const Predictor>(std::make_shared<ModelPredictor>(std::move(*model), perChannel));
    }};

// Its planes, its basis; rbf and bln: their weight grid's rows (ptm and hsh: in closed form).
void ModelPredictor::materialFields(nlohmann::json& predictor, const EngineParts& parts) const {
    predictor["images_layout"] =
        "RGBA8, planes four to an image (plane p: image p / 4, channel p % 4); value_p = (code_p - bias[p]) * "
        "scale[p], code 0 .. 255";
    predictor["basis"] = lightBasisName(parts.basis);
    predictor["basis_index"] = static_cast<int>(parts.basis);
    if (parts.basis == LightBasis::Hsh) predictor["order"] = parts.order;
    if (parts.weights > 0)
        predictor["weights"]["row"] =
            "the channels' offsets, then each plane's channel weights ((1 + planes) x channels)";
}

std::string LightModelFit::settings() const {
    const LightModelOptions& m = m_options;
    return "model " + std::to_string(static_cast<int>(m.basis)) + " " + std::to_string(m.order) + " " +
           std::to_string(m.planes) + " " + std::to_string(m.packed) + " " + std::to_string(m.grid) + " " +
           std::to_string(m.colour);
}

const FitKind& LightModelFit::kind() const { return kLightModelFit; }

namespace {
Result<LightModel> fittedLightModel(const LightModelOptions& options, const FitImages& in) {
    LightModelOptions o = options;
    o.threads = in.threads;
    return fitLightModel(in.images, in.lights, in.mask, o, in.what);
}
}  // namespace

Result<PredictorPointer> LightModelFit::fit(const FitImages& in) const {
    Result<LightModel> model = fittedLightModel(m_options, in);
    if (!model) return Error{model.error()};
    return PredictorPointer(std::make_shared<ModelPredictor>(std::move(*model), in.perChannel));
}

Result<UnmatchedModel> LightModelFit::fitUnmatched(const FitImages& in) const {
    Result<LightModel> model = fittedLightModel(m_options, in);
    if (!model) return Error{model.error()};
    auto m = std::make_shared<LightModel>(std::move(*model));
    return UnmatchedModel{[m](Direction light, Direction) { return m->render(light); },
                          static_cast<double>(m->bytesPerTexel()), static_cast<double>(m->multiplyAdds())};
}

FitPointer lightModelFit(LightModelOptions options) { return std::make_shared<LightModelFit>(std::move(options)); }

const FitKind kLightModelFit{
    fitNamed<lightModelNamed, lightModelFit>, false, false, [](const CandidateBounds& bounds) {
        const int albedo = bounds.channels == 3 ? 3 : 0;
        std::vector<FitCandidate> out;
        // A plane (or the albedo's channel) a byte, a multiply-add each.
        auto add = [&](std::string name, LightModelOptions m, int bytes) {
            out.push_back({std::move(name), lightModelFit(m), bytes, static_cast<std::size_t>(bytes)});
        };
        add("ptm", {.basis = LightBasis::Ptm}, 6 + albedo);
        add("hsh2", {.basis = LightBasis::Hsh, .order = 2}, 4 + albedo);
        add("hsh3", {.basis = LightBasis::Hsh, .order = 3}, 9 + albedo);
        const int planes = std::clamp(bounds.bytes, 1, LightModel::kMaxPlanes);
        const std::string n = std::to_string(planes);
        add("rbf" + n, {.basis = LightBasis::Rbf, .planes = planes}, planes);
        add("bln" + n, {.basis = LightBasis::Bilinear, .planes = planes}, planes);
        // Packed: the same bytes holding more components, the trailing ones with 4 bits.
        add("rbf" + n + "c", {.basis = LightBasis::Rbf, .planes = planes, .packed = true}, planes);
        add("bln" + n + "c", {.basis = LightBasis::Bilinear, .planes = planes, .packed = true}, planes);
        return out;
    }};

}  // namespace btflut
