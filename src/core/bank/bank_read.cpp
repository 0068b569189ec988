// Reading .btflut files (bank_file.h): every field checked before it is used.
#include "core/bank/bank_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/bank/bank_reader.h"
#include "core/check.h"
#include "core/io/json_text.h"
#include "core/predict/kind_chunk.h"
#include "core/predict/model_predictor.h"

namespace btflut {

using namespace bank_format;
using namespace bank_read;

namespace {

// The chunks of a .btflut file, each checked against its CRC; HEAD first, END last.
struct Chunks {
    std::uint32_t version = 0;
    std::vector<Chunk> list;
};

Result<Chunks> splitChunks(const Bytes& bytes, const std::string& name) {
    auto fail = [&](const std::string& what) { return Error{name + ": " + what}; };
    if (bytes.size() < sizeof kSignature + 4 || std::memcmp(bytes.data(), kSignature, 8) != 0)
        return fail("not a .btflut file (bad signature)");
    ByteReader file(bytes.data() + 8, bytes.size() - 8);
    Chunks chunks;
    chunks.version = file.get<std::uint32_t>();
    if (chunks.version < 1 || chunks.version > kBankFormatVersion)
        return fail("unsupported .btflut version " + std::to_string(chunks.version) + " (this btflut reads 1 to " +
                    std::to_string(kBankFormatVersion) + ")");
    for (;;) {
        if (file.remaining() == 0) return fail("truncated (no END chunk)");
        auto tag = file.get<std::uint32_t>();
        auto length = file.get<std::uint32_t>();
        if (!file.ok()) return fail("truncated (incomplete chunk header)");
        const std::uint8_t* payload = file.getBytes(length);
        auto storedCrc = file.get<std::uint32_t>();
        if (!file.ok())
            return fail("truncated (chunk " + tagName(tag) + " declares " + std::to_string(length) + " bytes)");
        if (chunkCrc(tag, payload, length) != storedCrc && !kFuzzingBuild)
            return fail("checksum mismatch in chunk " + tagName(tag) + " (file is corrupted)");
        if (chunks.list.empty() && tag != kHead) return fail("first chunk is not HEAD");
        if (tag == kEnd) {
            if (length != 0) return fail("END chunk is not empty");
            if (file.remaining() != 0) return fail("unexpected bytes after the END chunk");
            return chunks;
        }
        chunks.list.push_back({tag, payload, length});
    }
}

Result<Head> readHead(const Chunk& chunk, std::uint32_t version, const std::string& name, LutBank& bank) {
    auto fail = [&](const std::string& what) { return Error{name + ": " + what}; };
    ByteReader in(chunk.payload, chunk.length);
    Head head;
    head.version = version;
    bank.entries = static_cast<int>(in.get<std::uint32_t>());
    const auto colour = in.get<std::uint32_t>();
    bank.gridSize = static_cast<int>(in.get<std::uint32_t>());
    head.layerCount = in.get<std::uint32_t>();
    head.embedded = in.get<std::uint32_t>() == 1;
    head.refWidth = in.get<std::uint32_t>();
    head.refHeight = in.get<std::uint32_t>();
    head.refChannels = in.get<std::uint32_t>();
    head.refDepth = in.get<std::uint32_t>();
    Result<Direction> rl = in.getDirection(name, "reference light");
    Result<Direction> rv = in.getDirection(name, "reference view");
    bank.referenceName = in.getString();
    const auto domain = version >= 2 ? in.get<std::uint32_t>() : 0u;
    if (version >= 3) {
        head.references = in.get<std::uint32_t>();
        const auto regions = in.get<std::uint32_t>(), quantiles = in.get<std::uint32_t>();
        if (in.ok() && quantiles > 0) {
            // references 0: the PTM is the predictor (a PTMC chunk must follow)
            if (head.references > 255 || regions < 1 || regions > 255 || quantiles < 2 || quantiles > 65536)
                return fail("references, regions or quantiles out of range");
            bank.prediction.regions = static_cast<int>(regions);
            bank.prediction.quantiles = static_cast<int>(quantiles);
            if (head.references == 0) head.predictor = FilePredictor::Ptm;
        } else if (in.ok() && (head.references != 0 || regions != 0)) {
            return fail("references and regions without quantiles");
        }
    }
    if (version >= 5) {
        const auto predictor = in.get<std::uint32_t>();
        const auto match = in.get<float>();
        const auto target = in.get<std::uint32_t>();
        const KindChunk* own = kindChunkNumbered(predictor);
        const bool known =
            predictor <= static_cast<std::uint32_t>(FilePredictor::Ptm) || (own && own->since <= version);
        if (in.ok() && (!known || !(match >= 0 && match <= 1) || target > 1 ||
                        (bank.prediction.quantiles > 0 ? (head.references == 0) != (predictor != 0)
                                                       : predictor != 0 || match != 1 || target != 0)))
            return fail("predictor, match or target out of range, or not what the references say");
        if (bank.prediction.quantiles > 0) head.predictor = static_cast<FilePredictor>(predictor);
        bank.prediction.match = match;
        bank.prediction.target = static_cast<LutBank::Prediction::Target>(target);
    }
    if (!in.ok() || in.remaining() != 0) return fail("HEAD chunk has the wrong size");
    if (!rl) return Error{rl.error()};
    if (!rv) return Error{rv.error()};
    bank.referenceLight = *rl;
    bank.referenceView = *rv;
    if (bank.entries < 2 || static_cast<std::uint32_t>(bank.entries) > kMaxEntries)
        return fail("LUT entry count " + std::to_string(bank.entries) + " is invalid");
    if (colour != 1 && colour != 3 && !(colour == 4 && bank.makesLuts()))
        return fail("colour mode " + std::to_string(colour) + " is invalid");
    bank.colour = static_cast<ColourMode>(colour);
    if (bank.gridSize < 2 || static_cast<std::uint32_t>(bank.gridSize) > kMaxGrid)
        return fail("grid size " + std::to_string(bank.gridSize) + " is invalid");
    if (head.layerCount == 0) return fail("bank has no view layers");
    if (head.layerCount > kMaxBankNodes)
        return fail("bank declares " + std::to_string(head.layerCount) + " view layers, over the format's limit of " +
                    std::to_string(kMaxBankNodes));
    if ((head.refChannels != 1 && head.refChannels != 3) || (head.refDepth != 8 && head.refDepth != 16))
        return fail("reference image description is invalid");
    if (Status s = checkImageSize(head.refWidth, head.refHeight, name + ": reference image"); !s)
        return Error{s.error()};
    if (domain > 1) return fail("interpolation domain " + std::to_string(domain) + " is invalid");
    bank.domain = static_cast<BankDomain>(domain);
    return head;
}

}  // namespace

namespace {

// Which layers' LUTs to decode for `options.views`: from the layers' view directions alone
// (their first 16 bytes). Empty: every layer (no views asked, the isotropic domain, where
// every layer takes part in every lookup, or layers too malformed to tell; the checks of
// the chunks then say what is wrong).
std::vector<bool> wantedLayers(const Chunks& chunks, const Head& head, const LutBank& bank, const std::string& name,
                               const BankReadOptions& options) {
    if (options.views.empty() || bank.domain != BankDomain::Layers) return {};
    LutBank views;
    for (const Chunk& chunk : chunks.list) {
        if (chunk.tag != kLayer) continue;
        ByteReader in(chunk.payload, chunk.length);
        Result<Direction> view = in.getDirection(name, "layer view");
        if (!view || views.layers.size() == head.layerCount) return {};
        views.layers.push_back({*view, {}, {}, {}, {}, {}});
    }
    if (views.layers.empty()) return {};
    std::vector<DiskPoint> points;
    for (const ViewLayer& layer : views.layers) points.push_back(toDisk(layer.view));
    if (hasNearDuplicates(points, 1e-9)) return {};
    views.views = Triangulation(std::move(points));
    std::vector<bool> wanted(views.layers.size(), false);
    for (Direction v : options.views)
        for (std::size_t l : views.layersFor(v)) wanted[l] = true;
    return wanted;
}

// One decode after HEAD: a method per chunk after it (each may say the file is wrong), then
// the checks of the whole.
class BankDecoder {
public:
    BankDecoder(const Chunks& chunks, const Head& head, const std::string& name, const BankReadOptions& options,
                LutBank& bank)
        : m_chunks(chunks),
          m_head(head),
          m_name(name),
          m_options(options),
          m_bank(bank),
          m_wanted(wantedLayers(chunks, head, bank, name, options)) {}

    Status chunk(const Chunk& chunk) {
        ByteReader in(chunk.payload, chunk.length);
        switch (chunk.tag) {
            case kHead:
                return fail("two HEAD chunks");
            case kLayer:
                return layer(in);
            case kFill:
                if (m_chunks.version < 4 || m_fill) return fail("unexpected FILL chunk");
                m_fill = &chunk;
                return success();
            case kReference:
                return reference(chunk);
            case kReferences:
            case kMask:
            case kLabels:
            case kAlbedo:
                if (!m_bank.makesLuts()) return fail("unexpected chunk " + tagName(chunk.tag));
                return readPredictionChunk(chunk.tag, in, m_name, m_head, m_bank, m_parts);
            case kMatchGrid:
                return matchGrid(chunk);
            case kSelection:
                return selection(in);
            case kTargetFit:
                return targetFit(in);
            case kPtm:
                return ptm(chunk);
            default:
                if (const KindChunk* own = kindChunkTagged(chunk.tag)) return ownChunk(*own, in);
                return fail("unknown chunk " + tagName(chunk.tag));
        }
    }

    /// After every chunk: what must be there, the FILL flags, the predictor, the directions.
    Status finish() {
        if (m_bank.layers.size() != m_head.layerCount)
            return fail("declares " + std::to_string(m_head.layerCount) + " layers but holds " +
                        std::to_string(m_bank.layers.size()));
        if (m_head.embedded && !m_haveReference) return fail("reference image chunk is missing");
        if (m_matchGrids != 0 && m_matchGrids != m_bank.layers.size())
            return fail("a match grid (MGRD) for some layers only");
        if (m_bank.domain == BankDomain::Isotropic) {
            if (!m_fits.empty()) m_bank.pairFit = std::move(m_fits.front());
        } else {
            for (std::size_t l = 0; l < m_fits.size(); ++l) m_bank.layers[l].fit = std::move(m_fits[l]);
        }
        if (m_fill)
            if (Status s = fillFlags(); !s) return s;
        if (!m_head.embedded) {  // keep the description, without pixels
            m_bank.reference.width = static_cast<int>(m_head.refWidth);
            m_bank.reference.height = static_cast<int>(m_head.refHeight);
            m_bank.reference.channels = static_cast<int>(m_head.refChannels);
            m_bank.reference.bitDepth = static_cast<int>(m_head.refDepth);
        }
        if (m_bank.colour != ColourMode::Grey && m_head.refChannels != 3)
            return fail(std::string(colourName(m_bank.colour)) + " bank with a grey reference image");
        if (m_bank.makesLuts())
            if (Status s = predictor(); !s) return s;
        std::vector<DiskPoint> views;
        for (const ViewLayer& l : m_bank.layers) views.push_back(toDisk(l.view));
        if (hasNearDuplicates(views, 1e-9)) return fail("two layers share one view direction");
        m_bank.buildTriangulations();
        if (!m_bank.followsLight())
            return fail(
                "the bank's directions cannot follow the light (one light per view, and no "
                "interpolation over the view)");
        return success();
    }

private:
    Error fail(const std::string& what) const { return Error{m_name + ": " + what}; }

    // LAYR: a view direction, its nodes' lights and names, their LUTs (or quantile
    // functions), the grid's provenance and LUTs.
    Status layer(ByteReader& in) {
        if (m_bank.layers.size() == m_head.layerCount)
            return fail("more LAYR chunks than the " + std::to_string(m_head.layerCount) + " declared");
        const std::string which = "layer " + std::to_string(m_bank.layers.size());
        const std::size_t length1 = m_bank.nodeLength();
        const auto cells = static_cast<std::size_t>(m_bank.gridSize) * m_bank.gridSize;
        ViewLayer layer;
        Result<Direction> view = in.getDirection(m_name, "layer view");
        if (!view) return Error{view.error()};
        layer.view = *view;
        auto nodes = in.get<std::uint32_t>();
        if (!in.ok() || nodes == 0 || nodes > in.remaining() / 20) return fail(which + " has an invalid node count");
        m_totalNodes += nodes;
        if (m_totalNodes > kMaxBankNodes)
            return fail("more than " + std::to_string(kMaxBankNodes) + " measured directions (the format's limit)");
        for (std::uint32_t n = 0; n < nodes; ++n) {
            Result<Direction> light = in.getDirection(m_name, "node light");
            if (!light) return Error{light.error()};
            std::string nodeName = in.getString();
            layer.nodes.push_back({nodeName, *light});
        }
        const std::uint8_t* luts = in.getBytes(nodes * length1 * sizeof(float));
        const std::uint8_t* kinds = in.getBytes(cells);
        const std::uint8_t* grid = in.getBytes(cells * length1 * sizeof(std::uint16_t));
        if (!in.ok() || in.remaining() != 0)
            return fail("LAYR chunk " + std::to_string(m_bank.layers.size()) + " has the wrong size");
        std::vector<DiskPoint> lights;
        for (const LightNode& node : layer.nodes) lights.push_back(toDisk(node.light));
        if (hasNearDuplicates(lights, 1e-9)) return fail("two nodes share one light direction");
        if (!m_wanted.empty() && !m_wanted[m_bank.layers.size()]) {
            layer.lutsLoaded = false;
            m_bank.layers.push_back(std::move(layer));
            return success();
        }
        layer.nodeLuts.resize(nodes * length1);
        std::memcpy(layer.nodeLuts.data(), luts, layer.nodeLuts.size() * sizeof(float));
        for (std::size_t k = 0; k < layer.nodeLuts.size(); k += m_bank.segmentLength())
            if (!isValidLut(&layer.nodeLuts[k], m_bank.segmentLength()))
                return fail(std::string(m_bank.makesLuts() ? "a quantile function" : "a LUT") +
                            " is not monotonic in [0, 1] (file is corrupted)");
        for (std::size_t g = 0; g < cells; ++g) {
            if (kinds[g] > (m_chunks.version >= 4 ? 3 : 2)) return fail("invalid grid node provenance");
            if (m_options.grids) layer.gridProvenance.push_back(static_cast<Provenance>(kinds[g]));
        }
        if (m_options.grids) {
            layer.gridLuts.resize(cells * length1);
            std::memcpy(layer.gridLuts.data(), grid, layer.gridLuts.size() * sizeof(std::uint16_t));
        }
        m_bank.layers.push_back(std::move(layer));
        return success();
    }

    // REFI: the reference image, a PNG of HEAD's size and channels.
    Status reference(const Chunk& chunk) {
        if (!m_head.embedded || m_haveReference) return fail("unexpected REFI chunk");
        m_haveReference = true;
        Result<Image> image =
            decodeImage(Bytes(chunk.payload, chunk.payload + chunk.length), m_name + " (reference image)",
                        static_cast<int>(m_head.refWidth), static_cast<int>(m_head.refHeight));
        if (!image) return Error{image.error()};
        if (static_cast<std::uint32_t>(image->channels) != m_head.refChannels)
            return fail("reference image does not match the header");
        m_bank.reference = std::move(*image);
        return success();
    }

    // A kind's own chunk (predict/kind_chunk.h: LMDL, LRND): the predictor of a bank of that kind.
    Status ownChunk(const KindChunk& own, ByteReader& in) {
        if (m_parts.haveOwnChunk || !m_bank.makesLuts() || static_cast<std::uint32_t>(m_head.predictor) != own.number)
            return fail(std::string("unexpected ") + own.tag + " chunk");
        m_parts.haveOwnChunk = true;
        Result<std::shared_ptr<const Predictor>> predictor =
            own.decode(in, chunkSource(own.tag), m_head.version, static_cast<int>(m_head.refChannels),
                       m_bank.colour == ColourMode::Rgb, m_bank.colour == ColourMode::Lrgb);
        if (!predictor) return Error{predictor.error()};
        m_parts.own = std::move(*predictor);
        return success();
    }

    // MGRD: one per layer, in order, after the layers: the LUTs over the grid of a bank with
    // a predictor.
    Status matchGrid(const Chunk& chunk) {
        const std::size_t cells = static_cast<std::size_t>(m_bank.gridSize) * static_cast<std::size_t>(m_bank.gridSize);
        const std::size_t lutLength = static_cast<std::size_t>(m_bank.entries);
        if (m_chunks.version < 5 || !m_bank.makesLuts() || m_matchGrids >= m_bank.layers.size() ||
            chunk.length != cells * m_bank.matchLength() * sizeof(std::uint16_t))
            return fail("unexpected MGRD chunk, or one of the wrong size");
        ViewLayer& layer = m_bank.layers[m_matchGrids++];
        if (!m_options.matchGrids || !layer.lutsLoaded) return success();
        layer.matchGridLuts.resize(chunk.length / sizeof(std::uint16_t));
        std::memcpy(layer.matchGridLuts.data(), chunk.payload, chunk.length);
        for (std::size_t at = 0; at < layer.matchGridLuts.size(); at += lutLength)
            if (!std::is_sorted(layer.matchGridLuts.begin() + static_cast<std::ptrdiff_t>(at),
                                layer.matchGridLuts.begin() + static_cast<std::ptrdiff_t>(at + lutLength)))
                return fail("a LUT of the match grid is not monotonic (file is corrupted)");
        return success();
    }

    // CHOS: how --predictor auto chose (JSON).
    Status selection(ByteReader& in) {
        if (m_haveSelection || m_chunks.version < 5) return fail("unexpected CHOS chunk");
        m_haveSelection = true;
        m_bank.selection = in.getString();
        if (!in.ok() || in.remaining() != 0) return fail("CHOS chunk has the wrong size");
        if (Result<nlohmann::json> parsed = parseJsonText(m_bank.selection, m_name + " (CHOS chunk)"); !parsed)
            return Error{parsed.error()};
        return success();
    }

    // TFIT: the choice of estimate between the lights (JSON) and each layer's fit, kept until
    // the layers are all read (finish); in the isotropic domain (version 7) one fit over the
    // pairs' points.
    Status targetFit(ByteReader& in) {
        const bool pairs = m_bank.domain == BankDomain::Isotropic;
        if (m_haveTargetFit || m_chunks.version < (pairs ? 7 : 6)) return fail("unexpected TFIT chunk");
        m_haveTargetFit = true;
        m_bank.targetChoice = in.getString();
        const auto layers = in.get<std::uint32_t>();
        if (!in.ok() || layers != (pairs ? 1 : m_head.layerCount))
            return fail(pairs ? "TFIT chunk: truncated, or not one fit over the pairs"
                              : "TFIT chunk: truncated, or not one fit per layer");
        if (!m_bank.targetChoice.empty())
            if (Result<nlohmann::json> parsed = parseJsonText(m_bank.targetChoice, m_name + " (TFIT chunk)"); !parsed)
                return Error{parsed.error()};
        const std::size_t length = m_bank.nodeLength();
        for (std::uint32_t l = 0; l < layers; ++l) {
            TargetFit fit{.domain = pairs ? FitDomain::Pair : FitDomain::Light};
            const auto degree = in.get<std::uint32_t>();
            if (!in.ok() || degree > static_cast<std::uint32_t>(kMaxFitDegree))
                return fail("TFIT chunk: truncated, or a fit of an invalid degree");
            fit.degree = static_cast<int>(degree);
            const std::size_t values = degree == 0 ? 0 : static_cast<std::size_t>(fit.termCount()) * length;
            if (values > in.remaining() / sizeof(float)) return fail("TFIT chunk: truncated coefficients");
            fit.coefficients.resize(values);
            if (values > 0)
                std::memcpy(fit.coefficients.data(), in.getBytes(values * sizeof(float)), values * sizeof(float));
            for (float c : fit.coefficients)
                if (!std::isfinite(c)) return fail("TFIT chunk: a coefficient is not finite");
            m_fits.push_back(std::move(fit));
        }
        if (in.remaining() != 0) return fail("TFIT chunk has the wrong size");
        return success();
    }

    // PTMC: the baseline PTM, decoded when asked for or when it is the predictor.
    Status ptm(const Chunk& chunk) {
        if (m_havePtm) return fail("two PTMC chunks");
        m_havePtm = true;
        m_bank.ptmInFile = true;
        if (!m_options.ptm && !(m_bank.makesLuts() && m_head.predictor == FilePredictor::Ptm))
            return success();  // the predictor's is needed
        ByteReader in(chunk.payload, chunk.length);
        Result<LightModel> ptm = decodePtmChunk(in, chunkSource("PTM"));
        if (!ptm) return Error{ptm.error()};
        m_bank.ptm = std::move(*ptm);
        return success();
    }

    // FILL (after the layers): which nodes the model filled, and its parameters.
    Status fillFlags() {
        ByteReader in(m_fill->payload, m_fill->length);
        m_bank.modelFill = in.getString();
        for (ViewLayer& layer : m_bank.layers) {
            bool seen = false;  // a modelled node: every later one must be too
            for (LightNode& node : layer.nodes) {
                const auto modelled = in.get<std::uint8_t>();
                if (modelled > 1 || (seen && modelled == 0))
                    return fail("FILL chunk: invalid node flags (modelled nodes follow the measured ones)");
                node.modelled = modelled == 1;
                seen = node.modelled;
            }
            if (!layer.nodes.empty() && layer.nodes.front().modelled)
                return fail("FILL chunk: a view layer without measured nodes");
        }
        if (!in.ok() || in.remaining() != 0 || m_bank.modelFill.empty()) return fail("FILL chunk has the wrong size");
        return success();
    }

    // A bank with a predictor: its parts all there and consistent, made into its predictor (a
    // PTM-predicted bank's PTM as a light model).
    Status predictor() {
        LutBank::Prediction& prediction = m_bank.prediction;
        const FilePredictor kind = m_head.predictor;
        if (kind == FilePredictor::Ptm && (!m_havePtm || m_bank.colour != ColourMode::Grey))
            return fail("a PTM-predicted bank without its PTM");
        const KindChunk* own = kindChunkNumbered(static_cast<std::uint32_t>(kind));
        if (own && !m_parts.own) return fail(own->missing);
        if (!m_head.embedded || m_parts.references.size() != m_head.references || prediction.mask.inside.empty() ||
            (prediction.regions > 1) != !prediction.labels.empty() ||
            (m_bank.colour == ColourMode::Lrgb) != !m_parts.albedo.samples.empty() ||
            (m_bank.layers.size() != 1 &&
             !(m_parts.own && m_parts.own->viewDependent() && m_bank.domain == BankDomain::Layers)))
            return fail(
                "the references, mask, labels or albedo of a bank that blends references are missing or do not fit, "
                "or it has several view layers and no predictor of views");
        for (std::uint8_t label : prediction.labels)
            if (label >= prediction.regions) return fail("a region label is beyond the bank's regions");
        const bool perChannel = m_bank.colour == ColourMode::Rgb;
        if (kind == FilePredictor::Ptm)
            prediction.predictor = std::make_shared<ModelPredictor>(m_bank.ptm, perChannel);
        else if (own)
            prediction.predictor = std::move(m_parts.own);
        else
            prediction.predictor = std::make_shared<ReferenceBlend>(
                std::move(m_parts.references), std::move(m_parts.lights), perChannel, std::move(m_parts.albedo));
        return success();
    }

    // Where a predictor's chunk is read: its errors name the file and `tag`.
    ChunkSource chunkSource(const std::string& tag) const {
        return {m_name, tag, static_cast<int>(m_head.refWidth), static_cast<int>(m_head.refHeight)};
    }

    const Chunks& m_chunks;
    const Head& m_head;
    const std::string& m_name;
    const BankReadOptions& m_options;
    LutBank& m_bank;
    const std::vector<bool> m_wanted;  // empty: every layer's LUTs
    bool m_haveReference = false, m_havePtm = false, m_haveSelection = false, m_haveTargetFit = false;
    std::vector<TargetFit> m_fits;  // TFIT's, one per layer
    PredictorParts m_parts;
    std::size_t m_matchGrids = 0, m_totalNodes = 0;
    const Chunk* m_fill = nullptr;
};

}  // namespace

Result<LutBank> decodeBank(const Bytes& bytes, const std::string& name, const BankReadOptions& options) {
    Result<Chunks> chunks = splitChunks(bytes, name);
    if (!chunks) return Error{chunks.error()};
    LutBank bank;
    Result<Head> head = readHead(chunks->list.front(), chunks->version, name, bank);
    if (!head) return Error{head.error()};
    BankDecoder decoder(*chunks, *head, name, options, bank);
    for (std::size_t c = 1; c < chunks->list.size(); ++c)
        if (Status s = decoder.chunk(chunks->list[c]); !s) return Error{s.error()};
    if (Status s = decoder.finish(); !s) return Error{s.error()};
    return bank;
}

Result<LutBank> loadBank(const std::string& path, const BankReadOptions& options) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    return decodeBank(*bytes, path, options);
}

Result<LightModel> loadBankPtm(const std::string& path) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    Result<Chunks> chunks = splitChunks(*bytes, path);
    if (!chunks) return Error{chunks.error()};
    LutBank description;
    Result<Head> head = readHead(chunks->list.front(), chunks->version, path, description);
    if (!head) return Error{head.error()};
    for (const Chunk& chunk : chunks->list)
        if (chunk.tag == kPtm) {
            ByteReader in(chunk.payload, chunk.length);
            return decodePtmChunk(in,
                                  {path, "PTM", static_cast<int>(head->refWidth), static_cast<int>(head->refHeight)});
        }
    return Error{path + ": the bank holds no PTM (bake it with --ptm)"};
}

}  // namespace btflut
