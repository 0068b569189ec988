// Decoding the chunks a bank with a predictor has beside the predictor's own (bank_reader.h):
// every count and size checked against HEAD before anything is allocated.
#include <algorithm>
#include <cmath>

#include "core/bank/bank_reader.h"
#include "core/predict/chunk_planes.h"

namespace btflut::bank_read {

// The chunks of version 3 banks that make their LUTs at run time (LutBank::Prediction); sizes
// are checked against HEAD before anything is decoded, and each chunk may come once.
Status readPredictionChunk(std::uint32_t tag, ByteReader& in, const std::string& name, const Head& head, LutBank& bank,
                           PredictorParts& parts) {
    const int w = static_cast<int>(head.refWidth), h = static_cast<int>(head.refHeight);
    const ChunkSource source{name, tagName(tag), w, h};
    auto fail = [&](const std::string& what) { return source.fail(what); };
    LutBank::Prediction& prediction = bank.prediction;
    auto png = [&](const std::string& what) { return readPng(in, source, what, name + " (" + what + ")"); };
    auto whole = [&](const std::string& what) -> Result<Image> {  // a chunk that is one PNG
        const std::size_t length = in.remaining();
        const std::uint8_t* bytes = in.getBytes(length);
        return decodeImage(Bytes(bytes, bytes + length), name + " (" + what + ")", w, h);
    };
    if (tag == kReferences) {
        if (!parts.references.empty()) return fail("twice");
        for (std::uint32_t k = 0; k < head.references; ++k) {
            Result<Direction> light = in.getDirection(name, "reference light");
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
