// Writing .btflut files (bank_file.h; the reader is bank_read.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "core/bank/bank_file.h"
#include "core/bank/bank_format.h"
#include "core/check.h"
#include "core/predict/kind_chunk.h"
#include "core/predict/ptm.h"
#include "core/predict/reference_blend.h"

namespace btflut {

using namespace bank_format;

namespace {

void putChunk(ByteWriter& file, std::uint32_t tag, const Bytes& payload) {
    file.put(tag);
    file.put(static_cast<std::uint32_t>(payload.size()));
    file.putBytes(payload.data(), payload.size());
    file.put(chunkCrc(tag, payload.data(), payload.size()));
}

// The kind's own chunk (predict/kind_chunk.h); null for the references and a bank of LUTs.
const KindChunk* ownChunk(const LutBank& bank) { return kindChunkOf(bank.predictorKind()); }

bool anyLayer(const LutBank& bank, bool (*uses)(const ViewLayer&)) {
    return std::any_of(bank.layers.begin(), bank.layers.end(), uses);
}

// Each version and what it added (docs/btflut-format.md), newest first.
struct VersionAdded {
    std::uint32_t version;
    bool (*uses)(const LutBank&);
};
constexpr VersionAdded kVersionsAdded[] = {
    {7, [](const LutBank& b) { return !b.pairFit.empty(); }},  // the isotropic domain's fit
    {6, [](const LutBank& b) { return anyLayer(b, [](const ViewLayer& l) { return !l.fit.empty(); }); }},
    // A match in part, a target of corrections, auto's choice, match LUTs over the grid.
    {5,
     [](const LutBank& b) {
         return (b.makesLuts() &&
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
    // stay readable where they were: the choice's figures are then not kept.) A kind with a
    // chunk of its own says the version it needs.
    const KindChunk* own = ownChunk(bank);
    const std::uint32_t kindVersion = own ? own->version(bank.predictor()) : 1;
    for (const VersionAdded& v : kVersionsAdded)
        if (v.uses(bank)) return std::max(v.version, kindVersion);
    return kindVersion;
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
    ByteWriter file;
    file.putBytes(kSignature, sizeof kSignature);
    file.put(version);

    const bool embed = options.embedReference && !bank.reference.samples.empty();
    ByteWriter head;
    head.put(static_cast<std::uint32_t>(bank.entries));
    head.put(static_cast<std::uint32_t>(bank.colour));
    head.put(static_cast<std::uint32_t>(bank.gridSize));
    head.put(static_cast<std::uint32_t>(bank.layers.size()));
    head.put(static_cast<std::uint32_t>(embed ? 1 : 0));
    head.put(static_cast<std::uint32_t>(bank.reference.width));
    head.put(static_cast<std::uint32_t>(bank.reference.height));
    head.put(static_cast<std::uint32_t>(bank.reference.channels));
    head.put(static_cast<std::uint32_t>(bank.reference.bitDepth));
    head.putDirection(bank.referenceLight);
    head.putDirection(bank.referenceView);
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
        const KindChunk* own = ownChunk(bank);
        head.put(own ? own->number : static_cast<std::uint32_t>(FilePredictor::References));
        head.put(bank.makesLuts() ? bank.prediction.match : 1.f);
        head.put(static_cast<std::uint32_t>(bank.makesLuts() ? bank.prediction.target
                                                             : LutBank::Prediction::Target::Measured));
    }
    putChunk(file, kHead, head.bytes());

    for (const ViewLayer& layer : bank.layers) {
        BTFLUT_CHECK(layer.lutsLoaded && !layer.gridLuts.empty());  // read whole (BankReadOptions defaults)
        ByteWriter w;
        w.putDirection(layer.view);
        w.put(static_cast<std::uint32_t>(layer.nodes.size()));
        for (const LightNode& node : layer.nodes) {
            w.putDirection(node.light);
            w.putString(node.name);
        }
        w.putBytes(layer.nodeLuts.data(), layer.nodeLuts.size() * sizeof(float));
        for (Provenance p : layer.gridProvenance) w.put(static_cast<std::uint8_t>(p));
        w.putBytes(layer.gridLuts.data(), layer.gridLuts.size() * sizeof(std::uint16_t));
        putChunk(file, kLayer, w.bytes());
    }
    if (!bank.modelFill.empty()) {  // version 4: which nodes the model filled, and the model
        ByteWriter w;
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
            ByteWriter refs;
            for (std::size_t k = 0; k < references->references().size(); ++k) {
                const Image& image = references->references()[k];
                refs.putDirection(references->lights()[k].light);
                refs.putString(references->lights()[k].name);
                putPng(refs, image, image.bitDepth);
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
        if (const KindChunk* own = ownChunk(bank))
            putChunk(file, tagOf(own->tag), own->encode(bank.predictor(), version));
    }
    for (const ViewLayer& layer : bank.layers)  // version 5: every layer's or none
        if (!layer.matchGridLuts.empty())
            putChunk(
                file, kMatchGrid,
                Bytes(reinterpret_cast<const std::uint8_t*>(layer.matchGridLuts.data()),
                      reinterpret_cast<const std::uint8_t*>(layer.matchGridLuts.data() + layer.matchGridLuts.size())));
    if (!bank.selection.empty()) {
        ByteWriter w;
        w.putString(bank.selection);
        putChunk(file, kSelection, w.bytes());
    }
    if (version >= 6) {  // how the targets are estimated between the lights, and each layer's fit
        ByteWriter w;
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
    if (!bank.ptm.empty()) putChunk(file, kPtm, encodePtmChunk(bank.ptm));
    putChunk(file, kEnd, {});
    return std::move(file.bytes());
}

Status saveBank(const LutBank& bank, const std::string& path, const BankWriteOptions& options) {
    if (Status s = checkBankSize(bank); !s) return Error{path + ": " + s.error()};
    return writeFileAtomically(path, encodeBank(bank, options));
}

}  // namespace btflut
