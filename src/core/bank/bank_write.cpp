// Writing .btflut files (bank_file.h; the reader is bank_read.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "core/bank/bank_file.h"
#include "core/bank/bank_format.h"
#include "core/check.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/model_predictor.h"
#include "core/predict/reference_blend.h"

namespace btflut {

using namespace bank_format;

namespace {

class Writer {
public:
    template <typename T>
    void put(T v) {
        auto p = reinterpret_cast<const std::uint8_t*>(&v);
        m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
    }
    void putBytes(const void* data, std::size_t n) {
        if (n == 0) return;
        auto p = static_cast<const std::uint8_t*>(data);
        m_bytes.insert(m_bytes.end(), p, p + n);
    }
    void putString(const std::string& s) {
        put(static_cast<std::uint32_t>(s.size()));
        putBytes(s.data(), s.size());
    }
    Bytes& bytes() { return m_bytes; }

private:
    Bytes m_bytes;
};

void putChunk(Writer& file, std::uint32_t tag, const Bytes& payload) {
    file.put(tag);
    file.put(static_cast<std::uint32_t>(payload.size()));
    file.putBytes(payload.data(), payload.size());
    file.put(chunkCrc(tag, payload.data(), payload.size()));
}

void putDirection(Writer& w, Direction d) {
    w.put(d.thetaDegrees());
    w.put(d.phiDegrees());
}

// PTMC payload: width, height (u32), scale[6], bias[6] (f32), then three PNGs, each
// preceded by its byte length (u32): coefficients 0-2, coefficients 3-5, albedo (RGB8).
Bytes encodePtm(const LightModel& ptm) {
    Writer w;
    w.put(static_cast<std::uint32_t>(ptm.width));
    w.put(static_cast<std::uint32_t>(ptm.height));
    for (float v : ptm.scale) w.put(v);
    for (float v : ptm.bias) w.put(v);
    for (const Image& image : lightModelImages(ptm)) {  // coefficients 0-2, 3-5, the albedo
        const Bytes png = encodePng(image, 8);
        w.put(static_cast<std::uint32_t>(png.size()));
        w.putBytes(png.data(), png.size());
    }
    return std::move(w.bytes());
}

// LMDL payload (docs/btflut-format.md): the model's description, its per-light table, then
// its planes three to an RGB PNG and, in the LRGB layout, the albedo.
Bytes encodeLightModel(const LightModel& m) {
    Writer w;
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
    for (Direction d : m.lights) putDirection(w, d);
    w.put(static_cast<std::uint32_t>(m.table.size()));
    w.putBytes(m.table.data(), m.table.size() * sizeof(float));
    for (const Image& image : lightModelImages(m)) {  // the planes, then the albedo
        const Bytes bytes = encodePng(image, 8);
        w.put(static_cast<std::uint32_t>(bytes.size()));
        w.putBytes(bytes.data(), bytes.size());
    }
    return std::move(w.bytes());
}

// LRND payload (docs/btflut-format.md): the model's sizes (version 9: with its view features),
// each code's scale and bias, the light network's and the residual network's parameters, then
// the codes three to an RGB PNG.
Bytes encodeLearnedModel(const LearnedModel& m, std::uint32_t version) {
    BTFLUT_CHECK(version >= 9 || m.viewFeatures == 0);
    Writer w;
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
        const Bytes png = encodePng(image, 8);
        w.put(static_cast<std::uint32_t>(png.size()));
        w.putBytes(png.data(), png.size());
    }
    return std::move(w.bytes());
}

// The HEAD's predictor: References for a bank of LUTs too.
FilePredictor filePredictor(const LutBank& bank) {
    switch (bank.predictorKind()) {
        case PredictorKind::Learned:
            return FilePredictor::Learned;
        case PredictorKind::Model:
            return FilePredictor::Model;
        case PredictorKind::Luts:
        case PredictorKind::References:
            break;
    }
    return FilePredictor::References;
}

bool anyLayer(const LutBank& bank, bool (*uses)(const ViewLayer&)) {
    return std::any_of(bank.layers.begin(), bank.layers.end(), uses);
}

// Each version and what it added (docs/btflut-format.md), newest first.
struct VersionAdded {
    std::uint32_t version;
    bool (*uses)(const LutBank&);
};
constexpr VersionAdded kVersionsAdded[] = {
    {9, [](const LutBank& b) { return filePredictor(b) == FilePredictor::Learned && b.predictor().viewDependent(); }},
    {8, [](const LutBank& b) { return filePredictor(b) == FilePredictor::Learned; }},
    {7, [](const LutBank& b) { return !b.pairFit.empty(); }},  // the isotropic domain's fit
    {6, [](const LutBank& b) { return anyLayer(b, [](const ViewLayer& l) { return !l.fit.empty(); }); }},
    // A light model, a match in part, a target of corrections, auto's choice, match LUTs over the grid.
    {5,
     [](const LutBank& b) {
         return filePredictor(b) == FilePredictor::Model ||
                (b.makesLuts() &&
                 (b.prediction.match != 1 || b.prediction.target != LutBank::Prediction::Target::Measured)) ||
                !b.selection.empty() || anyLayer(b, [](const ViewLayer& l) { return !l.matchGridLuts.empty(); });
     }},
    {4, [](const LutBank& b) { return !b.modelFill.empty(); }},
    {3, [](const LutBank& b) { return b.makesLuts(); }},
    {2, [](const LutBank& b) { return b.domain != BankDomain::Layers; }},
};

}  // namespace

std::uint32_t bankFormatVersion(const LutBank& bank) {
    // The oldest version that holds everything: readers of version 1 keep reading the banks
    // they always could. (A choice of the blend everywhere changes no lookup, and such banks
    // stay readable where they were: the choice's figures are then not kept.)
    for (const VersionAdded& v : kVersionsAdded)
        if (v.uses(bank)) return v.version;
    return 1;
}

Status checkBankSize(const LutBank& bank) {
    const std::uint64_t length = bank.nodeLength(), cells = static_cast<std::uint64_t>(bank.gridSize) * bank.gridSize;
    for (const ViewLayer& layer : bank.layers) {
        std::uint64_t bytes = 20 + layer.nodes.size() * (20 + length * 4) + cells * (1 + length * 2);
        for (const LightNode& node : layer.nodes) bytes += node.name.size();
        if (bytes > kMaxChunk)
            return Error{"a view layer of " + std::to_string(layer.nodes.size()) + " lights with a " +
                         std::to_string(bank.gridSize) + "x" + std::to_string(bank.gridSize) + " grid of " +
                         std::to_string(bank.entries) + "-entry LUTs takes " + std::to_string(bytes) +
                         " bytes, over the .btflut format's 4 GiB chunk limit (use a smaller --grid or --entries)"};
    }
    std::size_t nodes = 0;
    for (const ViewLayer& layer : bank.layers) nodes += layer.nodes.size();
    if (nodes > kMaxBankNodes)
        return Error{"the bank would hold " + std::to_string(nodes) +
                     " measured directions, over the format's limit of " + std::to_string(kMaxBankNodes)};
    return success();
}

Bytes encodeBank(const LutBank& bank, const BankWriteOptions& options) {
    BTFLUT_CHECK(checkBankSize(bank).ok());
    const std::uint32_t version = bankFormatVersion(bank);
    Writer file;
    file.putBytes(kSignature, sizeof kSignature);
    file.put(version);

    const bool embed = options.embedReference && !bank.reference.samples.empty();
    Writer head;
    head.put(static_cast<std::uint32_t>(bank.entries));
    head.put(static_cast<std::uint32_t>(bank.colour));
    head.put(static_cast<std::uint32_t>(bank.gridSize));
    head.put(static_cast<std::uint32_t>(bank.layers.size()));
    head.put(static_cast<std::uint32_t>(embed ? 1 : 0));
    head.put(static_cast<std::uint32_t>(bank.reference.width));
    head.put(static_cast<std::uint32_t>(bank.reference.height));
    head.put(static_cast<std::uint32_t>(bank.reference.channels));
    head.put(static_cast<std::uint32_t>(bank.reference.bitDepth));
    putDirection(head, bank.referenceLight);
    putDirection(head, bank.referenceView);
    head.putString(bank.referenceName);
    if (version >= 2) head.put(static_cast<std::uint32_t>(bank.domain));
    if (version >= 3) {
        // All zero for a bank of LUTs (a version 4 bank need not make its LUTs at run time).
        const ReferenceBlend* references = bank.predictorAs<ReferenceBlend>();
        head.put(static_cast<std::uint32_t>(references ? references->references().size() : 0));
        head.put(static_cast<std::uint32_t>(bank.makesLuts() ? bank.prediction.regions : 0));
        head.put(static_cast<std::uint32_t>(bank.prediction.quantiles));
    }
    if (version >= 5) {
        head.put(static_cast<std::uint32_t>(filePredictor(bank)));
        head.put(bank.makesLuts() ? bank.prediction.match : 1.f);
        head.put(static_cast<std::uint32_t>(bank.makesLuts() ? bank.prediction.target
                                                             : LutBank::Prediction::Target::Measured));
    }
    putChunk(file, kHead, head.bytes());

    for (const ViewLayer& layer : bank.layers) {
        BTFLUT_CHECK(layer.lutsLoaded && !layer.gridLuts.empty());  // read whole (BankReadOptions defaults)
        Writer w;
        putDirection(w, layer.view);
        w.put(static_cast<std::uint32_t>(layer.nodes.size()));
        for (const LightNode& node : layer.nodes) {
            putDirection(w, node.light);
            w.putString(node.name);
        }
        w.putBytes(layer.nodeLuts.data(), layer.nodeLuts.size() * sizeof(float));
        for (Provenance p : layer.gridProvenance) w.put(static_cast<std::uint8_t>(p));
        w.putBytes(layer.gridLuts.data(), layer.gridLuts.size() * sizeof(std::uint16_t));
        putChunk(file, kLayer, w.bytes());
    }
    if (!bank.modelFill.empty()) {  // version 4: which nodes the model filled, and the model
        Writer w;
        w.putString(bank.modelFill);
        for (const ViewLayer& layer : bank.layers)
            for (const LightNode& node : layer.nodes) w.put(static_cast<std::uint8_t>(node.modelled ? 1 : 0));
        putChunk(file, kFill, w.bytes());
    }
    if (embed) putChunk(file, kReference, encodePng(bank.reference, bank.reference.bitDepth));
    if (bank.makesLuts()) {
        const LutBank::Prediction& prediction = bank.prediction;
        const ReferenceBlend* references = bank.predictorAs<ReferenceBlend>();
        if (references) {
            Writer refs;
            for (std::size_t k = 0; k < references->references().size(); ++k) {
                const Image& image = references->references()[k];
                putDirection(refs, references->lights()[k].light);
                refs.putString(references->lights()[k].name);
                const Bytes png = encodePng(image, image.bitDepth);
                refs.put(static_cast<std::uint32_t>(png.size()));
                refs.putBytes(png.data(), png.size());
            }
            putChunk(file, kReferences, refs.bytes());
        }
        putChunk(file, kMask,
                 encodePng(byteImage(prediction.mask.inside, prediction.mask.width, prediction.mask.height, 255), 8));
        if (!prediction.labels.empty())
            putChunk(file, kLabels,
                     encodePng(byteImage(prediction.labels, prediction.mask.width, prediction.mask.height, 1), 8));
        if (references && !references->albedo().samples.empty())
            putChunk(file, kAlbedo, encodePng(references->albedo(), 8));
        if (filePredictor(bank) == FilePredictor::Model)
            putChunk(file, kLightModel, encodeLightModel(bank.predictorAs<ModelPredictor>()->model()));
        if (filePredictor(bank) == FilePredictor::Learned)
            putChunk(file, kLearnedModel, encodeLearnedModel(bank.predictorAs<LearnedPredictor>()->model(), version));
    }
    for (const ViewLayer& layer : bank.layers)  // version 5: every layer's or none
        if (!layer.matchGridLuts.empty())
            putChunk(
                file, kMatchGrid,
                Bytes(reinterpret_cast<const std::uint8_t*>(layer.matchGridLuts.data()),
                      reinterpret_cast<const std::uint8_t*>(layer.matchGridLuts.data() + layer.matchGridLuts.size())));
    if (!bank.selection.empty()) {
        Writer w;
        w.putString(bank.selection);
        putChunk(file, kSelection, w.bytes());
    }
    if (version >= 6) {  // how the targets are estimated between the lights, and each layer's fit
        Writer w;
        w.putString(bank.targetChoice);
        auto put = [&](const TargetFit& fit) {
            w.put(static_cast<std::uint32_t>(fit.degree));
            w.putBytes(fit.coefficients.data(), fit.coefficients.size() * sizeof(float));
        };
        if (bank.domain == BankDomain::Isotropic) {  // one fit over the pairs' points
            w.put(std::uint32_t{1});
            put(bank.pairFit);
        } else {
            w.put(static_cast<std::uint32_t>(bank.layers.size()));
            for (const ViewLayer& layer : bank.layers) put(layer.fit);
        }
        putChunk(file, kTargetFit, w.bytes());
    }
    if (!bank.ptm.empty()) putChunk(file, kPtm, encodePtm(bank.ptm));
    putChunk(file, kEnd, {});
    return std::move(file.bytes());
}

Status saveBank(const LutBank& bank, const std::string& path, const BankWriteOptions& options) {
    if (Status s = checkBankSize(bank); !s) return Error{path + ": " + s.error()};
    return writeFileAtomically(path, encodeBank(bank, options));
}

}  // namespace btflut
