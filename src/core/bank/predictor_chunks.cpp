// Decoding the chunks of a bank's predictor and baseline (bank_reader.h): every count and size
// checked against HEAD before anything is allocated.
#include <algorithm>
#include <cmath>

#include "core/bank/bank_reader.h"
#include "core/check.h"
#include "core/predict/learned_decoder.h"

namespace btflut::bank_read {

Result<Direction> getDirection(Reader& in, const std::string& name, const std::string& what) {
    const double theta = in.get<double>(), phi = in.get<double>();
    if (!std::isfinite(theta) || !std::isfinite(phi) || theta < 0 || theta > 90)
        return Error{name + ": invalid " + what + " direction"};
    return Direction::fromDegrees(theta, phi);
}

namespace {

// A PNG stored as its length, then its bytes, decoded (the decoder refuses more than w x h);
// `what` names it in the chunk's errors (made by `fail`), `context` in the decoder's.
template <class Fail>
Result<Image> readPng(Reader& in, const Fail& fail, const std::string& what, const std::string& context, int w, int h) {
    const auto length = in.get<std::uint32_t>();
    const std::uint8_t* bytes = in.getBytes(length);
    if (!in.ok()) return fail("truncated " + what);
    return decodeImage(Bytes(bytes, bytes + length), context, w, h);
}

// The same, refused unless it is an RGB8 image of exactly w x h: a chunk's planes of codes.
template <class Fail>
Result<Image> readRgb8Plane(Reader& in, const Fail& fail, const std::string& what, const std::string& context, int w,
                            int h) {
    Result<Image> image = readPng(in, fail, what, context, w, h);
    if (image && (image->width != w || image->height != h || image->channels != 3 || image->bitDepth != 8))
        return fail(what + " is not an RGB8 image of the reference's size");
    return image;
}

// A light model's planes (m's sizes and an albedo of its size set), as lightModelImages
// writes them: its 8-bit planes three to an RGB8 PNG, its 4-bit planes six (two to a
// channel), then the albedo; `context` and `word` name them in errors.
template <class Fail>
Status readPlanes(Reader& in, const Fail& fail, const std::string& context, const std::string& word, LightModel& m) {
    auto png = [&](const std::string& what) {
        return readRgb8Plane(in, fail, what, context + what + ")", m.width, m.height);
    };
    const auto P = static_cast<std::size_t>(m.planes), W = static_cast<std::size_t>(m.wide);
    m.coefficients.resize(m.texels() * P);
    for (std::size_t first = 0; first < W; first += 3) {
        Result<Image> image = png(word + std::to_string(first) + "-" + std::to_string(std::min(W, first + 3) - 1));
        if (!image) return Error{image.error()};
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3 && first + c < W; ++c)
                m.coefficients[i * P + first + c] =
                    static_cast<std::uint8_t>(std::lround(image->samples[i * 3 + c] * 255));
    }
    for (std::size_t first = W; first < P; first += 6) {  // 4-bit planes, two to a channel
        Result<Image> image =
            png("4-bit " + word + std::to_string(first) + "-" + std::to_string(std::min(P, first + 6) - 1));
        if (!image) return Error{image.error()};
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3; ++c) {
                const auto code = static_cast<int>(std::lround(image->samples[i * 3 + c] * 255));
                if (first + 2 * c < P) m.coefficients[i * P + first + 2 * c] = static_cast<std::uint8_t>(code / 16);
                if (first + 2 * c + 1 < P)
                    m.coefficients[i * P + first + 2 * c + 1] = static_cast<std::uint8_t>(code % 16);
            }
    }
    if (!m.albedo.empty()) {
        Result<Image> image = png("albedo");
        if (!image) return Error{image.error()};
        for (std::size_t s = 0; s < m.albedo.size(); ++s)
            m.albedo[s] = static_cast<std::uint8_t>(std::lround(image->samples[s] * 255));
    }
    return success();
}

}  // namespace

// LMDL (encodeLightModel in bank_write.cpp): every count checked before anything is allocated
// by it, every number finite, the planes and albedo the reference's size.
Result<LightModel> decodeLightModel(Reader& in, const std::string& name, const Head& head) {
    auto fail = [&](const std::string& what) { return Error{name + ": LMDL chunk: " + what}; };
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
    m.width = static_cast<int>(head.refWidth);
    m.height = static_cast<int>(head.refHeight);
    const bool fixedBasis = m.basis == LightBasis::Ptm || m.basis == LightBasis::Hsh;
    if (fixedBasis &&
        (channels != 1 || (m.basis == LightBasis::Hsh ? order != 2 && order != 3 : order != 0) ||
         static_cast<int>(planes) != LightModel::termCount(m.basis, m.order) || grid != 0 || wide != planes))
        return fail("a " + std::string(lightBasisName(m.basis)) + " model with the wrong terms");
    // An albedo on a grey reference too: a bank's PTM (fitted with an albedo on grey images as
    // on colour ones) was the predictor of files before LMDL, and is written back as this.
    if (albedo ? head.refChannels != 3 && head.refChannels != 1 : channels != head.refChannels)
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
        Result<Direction> light = getDirection(in, name, "light model light");
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
    if (Status s = readPlanes(in, fail, name + " (light model ", "planes ", m); !s) return Error{s.error()};
    if (in.remaining() != 0) return fail("has the wrong size");
    return m;
}

// LRND (encodeLearnedModel in bank_write.cpp): every count checked before anything is
// allocated by it, the decoder's parameters as many as its sizes need and finite, the codes
// the reference's size.
Result<LearnedModel> decodeLearnedModel(Reader& in, const std::string& name, const Head& head) {
    auto fail = [&](const std::string& what) { return Error{name + ": LRND chunk: " + what}; };
    LearnedModel m;
    const auto codes = in.get<std::uint32_t>(), channels = in.get<std::uint32_t>();
    if (!in.ok() || codes < 1 || codes > static_cast<std::uint32_t>(LearnedModel::kMaxCodes) ||
        (channels != 1 && channels != 3) || channels > head.refChannels)
        return fail("invalid description");
    m.codes = static_cast<int>(codes);
    m.channels = static_cast<int>(channels);
    if (head.version >= 9) {  // a model of views takes the view's features too
        const auto views = in.get<std::uint32_t>();
        if (!in.ok() || (views != 0 && views != static_cast<std::uint32_t>(kLearnedViewFeatures)))
            return fail("invalid view feature count");
        m.viewFeatures = static_cast<int>(views);
    }
    m.width = static_cast<int>(head.refWidth);
    m.height = static_cast<int>(head.refHeight);
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
        Result<Image> image = readRgb8Plane(in, fail, what, name + " (learned " + what + ")", m.width, m.height);
        if (!image) return Error{image.error()};
        for (std::size_t i = 0; i < m.texels(); ++i)
            for (std::size_t c = 0; c < 3 && first + c < N; ++c)
                q.bytes[i * N + first + c] = static_cast<std::uint8_t>(std::lround(image->samples[i * 3 + c] * 255));
    }
    if (in.remaining() != 0) return fail("has the wrong size");
    return m;
}

// The PTM of a bank whose reference image is width x height (from HEAD, already checked
// against the pixel limit): its own size must match before anything is allocated.
Result<LightModel> decodePtm(const Chunk& chunk, const std::string& name, std::uint32_t width, std::uint32_t height) {
    auto fail = [&](const std::string& what) { return Error{name + ": PTM chunk: " + what}; };
    Reader in(chunk.payload, chunk.length);
    const auto w = in.get<std::uint32_t>(), h = in.get<std::uint32_t>();
    LightModel ptm;
    ptm.basis = LightBasis::Ptm;
    ptm.planes = ptm.wide = kPtmTerms;
    for (std::vector<float>* values : {&ptm.scale, &ptm.bias})
        for (int k = 0; k < kPtmTerms; ++k) values->push_back(in.get<float>());
    if (!in.ok()) return fail("invalid header");
    if (w != width || h != height)
        return Error{name + ": the PTM (" + std::to_string(w) + "x" + std::to_string(h) +
                     ") does not match the reference image's size"};
    ptm.width = static_cast<int>(w);
    ptm.height = static_cast<int>(h);
    for (std::size_t k = 0; k < ptm.scale.size(); ++k)
        if (!std::isfinite(ptm.scale[k]) || !std::isfinite(ptm.bias[k]) || ptm.scale[k] <= 0)
            return fail("invalid scale or bias");
    ptm.albedo.resize(ptm.texels() * 3);
    if (Status s = readPlanes(in, fail, name + " (PTM ", "coefficients ", ptm); !s) return Error{s.error()};
    if (in.remaining() != 0) return fail("has the wrong size");
    return ptm;
}

// The chunks of version 3 banks that make their LUTs at run time (LutBank::Prediction); sizes
// are checked against HEAD before anything is decoded, and each chunk may come once.
Status readPredictionChunk(std::uint32_t tag, Reader& in, const std::string& name, const Head& head, LutBank& bank,
                           PredictorParts& parts) {
    auto fail = [&](const std::string& what) { return Error{name + ": " + tagName(tag) + " chunk: " + what}; };
    LutBank::Prediction& prediction = bank.prediction;
    const int w = static_cast<int>(head.refWidth), h = static_cast<int>(head.refHeight);
    auto png = [&](const std::string& what) { return readPng(in, fail, what, name + " (" + what + ")", w, h); };
    auto whole = [&](const std::string& what) -> Result<Image> {  // a chunk that is one PNG
        const std::size_t length = in.remaining();
        const std::uint8_t* bytes = in.getBytes(length);
        return decodeImage(Bytes(bytes, bytes + length), name + " (" + what + ")", w, h);
    };
    if (tag == kReferences) {
        if (!parts.references.empty()) return fail("twice");
        for (std::uint32_t k = 0; k < head.references; ++k) {
            Result<Direction> light = getDirection(in, name, "reference light");
            if (!light) return Error{light.error()};
            std::string referenceName = in.getString();
            Result<Image> image = png("reference " + std::to_string(k));
            if (!image) return Error{image.error()};
            const int channels = bank.colour == ColourMode::Lrgb ? 1 : static_cast<int>(head.refChannels);
            if (image->channels != channels || image->bitDepth != 8)
                return fail("reference " + std::to_string(k) + " has the wrong channels or is not 8-bit");
            parts.lights.push_back({referenceName, *light});
            parts.references.push_back(std::move(*image));
        }
        if (in.remaining() != 0) return fail("has the wrong size");
        std::vector<DiskPoint> points;
        for (const ReferenceLight& l : parts.lights) points.push_back(toDisk(l.light));
        if (hasNearDuplicates(points, 1e-9)) return fail("two references share one light direction");
        return success();
    }
    if (tag == kMask || tag == kLabels) {
        if (!(tag == kMask ? prediction.mask.inside : prediction.labels).empty()) return fail("twice");
        Result<Image> image = whole(tag == kMask ? "mask" : "labels");
        if (!image) return Error{image.error()};
        if (image->channels != 1 || image->bitDepth != 8) return fail("not an 8-bit grey image");
        std::vector<std::uint8_t> bytes(image->pixelCount());
        for (std::size_t i = 0; i < bytes.size(); ++i)
            bytes[i] = static_cast<std::uint8_t>(std::lround(image->samples[i] * 255) / (tag == kMask ? 255 : 1));
        if (tag == kLabels) {
            prediction.labels = std::move(bytes);
            return success();
        }
        prediction.mask = {w, h, std::move(bytes)};
        if (prediction.mask.count() == 0) return fail("has no sample pixels");
        return success();
    }
    if (!parts.albedo.samples.empty()) return fail("twice");
    Result<Image> image = whole("albedo");
    if (!image) return Error{image.error()};
    if (image->channels != 3) return fail("not an RGB image");
    parts.albedo = std::move(*image);
    return success();
}

}  // namespace btflut::bank_read
