#include "core/predict/chunk_planes.h"

#include <algorithm>
#include <cmath>

namespace btflut {

void putPng(ByteWriter& w, const Image& image, int bitDepth) {
    const Bytes png = encodePng(image, bitDepth);
    w.put(static_cast<std::uint32_t>(png.size()));
    w.putBytes(png.data(), png.size());
}

Result<Image> readPng(ByteReader& in, const ChunkSource& source, const std::string& what, const std::string& context) {
    const auto length = in.get<std::uint32_t>();
    const std::uint8_t* bytes = in.getBytes(length);
    if (!in.ok()) return source.fail("truncated " + what);
    return decodeImage(Bytes(bytes, bytes + length), context, source.width, source.height);
}

Result<Image> readRgb8Plane(ByteReader& in, const ChunkSource& source, const std::string& what,
                            const std::string& context) {
    Result<Image> image = readPng(in, source, what, context);
    if (image && (image->width != source.width || image->height != source.height || image->channels != 3 ||
                  image->bitDepth != 8))
        return source.fail(what + " is not an RGB8 image of the reference's size");
    return image;
}

Status readModelPlanes(ByteReader& in, const ChunkSource& source, const std::string& context, const std::string& word,
                       LightModel& m) {
    auto png = [&](const std::string& what) { return readRgb8Plane(in, source, what, context + what + ")"); };
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

}  // namespace btflut
