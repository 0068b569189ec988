// The only place that sees stb_image and libspng: the rest of btflut gets owning Image values.
#include "core/image.h"

#include <spng.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO  // every read goes through readFile, so errors name the file
#define STBI_FAILURE_USERMSG
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_TGA
#define STBI_ONLY_BMP
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace btflut {

namespace {

std::uint32_t le16(const Bytes& b, std::size_t at) { return b[at] | (b[at + 1] << 8); }
std::uint32_t le32(const Bytes& b, std::size_t at) {
    return le16(b, at) | (static_cast<std::uint32_t>(le16(b, at + 2)) << 16);
}

// stb_image reads past the end of uncompressed TGA/BMP pixel data and of JPEG scans
// without complaint (it fills zeros), so truncation is checked here, per format.
std::string truncationProblem(const Bytes& b) {
    std::size_t n = b.size();
    if (n >= 2 && b[0] == 'B' && b[1] == 'M') {
        if (n < 34) return "truncated BMP header";
        std::uint64_t offset = le32(b, 10);
        std::int32_t w = static_cast<std::int32_t>(le32(b, 18));
        std::int32_t h = static_cast<std::int32_t>(le32(b, 22));
        std::uint32_t bpp = le16(b, 28), compression = le32(b, 30);
        if (compression == 0 || compression == 3) {
            std::uint64_t stride = ((static_cast<std::uint64_t>(std::abs(w)) * bpp + 31) / 32) * 4;
            if (offset + stride * static_cast<std::uint64_t>(std::abs(h)) > n)
                return "truncated BMP (pixel data ends early)";
        }
        return {};
    }
    if (n >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) {
        // The end-of-image marker must follow the last start-of-scan marker. Entropy-coded
        // data stuffs 0xFF as FF 00, so FF D9 there is a real marker.
        std::size_t lastScan = 0;
        for (std::size_t i = 2; i + 1 < n; ++i)
            if (b[i] == 0xFF && b[i + 1] == 0xDA) lastScan = i;
        for (std::size_t i = lastScan; i + 1 < n; ++i)
            if (b[i] == 0xFF && b[i + 1] == 0xD9) return {};
        return "truncated JPEG (no end-of-image marker)";
    }
    if (n >= 8 && b[0] == 0x89 && b[1] == 'P') {
        // stb stops at IEND without checking CRCs, so a cut in the last chunk goes unseen.
        for (std::size_t i = n >= 12 ? n - 12 : 0; i + 8 <= n; ++i)
            if (std::memcmp(&b[i], "IEND", 4) == 0 && i + 8 <= n) return {};
        return "truncated PNG (no complete IEND chunk)";
    }
    // Otherwise TGA, which has no magic number: check uncompressed pixel data length.
    if (n < 18) return "file too short to be an image";
    std::uint32_t type = b[2];
    if (type == 1 || type == 2 || type == 3) {
        std::uint64_t palette = b[1] ? le16(b, 5) * ((b[7] + 7u) / 8u) : 0;
        std::uint64_t pixels = static_cast<std::uint64_t>(le16(b, 12)) * le16(b, 14) *
                               ((b[16] + 7u) / 8u);
        if (18 + b[0] + palette + pixels > n) return "truncated TGA (pixel data ends early)";
    }
    return {};
}

}  // namespace

std::size_t Mask::count() const {
    return static_cast<std::size_t>(std::count_if(inside.begin(), inside.end(),
                                                  [](std::uint8_t v) { return v != 0; }));
}

Result<Image> decodeImage(const Bytes& bytes, const std::string& name) {
    if (bytes.empty()) return Error{name + ": empty file"};
    if (bytes.size() > static_cast<std::size_t>(INT32_MAX)) return Error{name + ": file too large"};
    auto len = static_cast<int>(bytes.size());
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &comp))
        return Error{name + ": not a readable PNG/JPEG/TGA/BMP image (" + stbi_failure_reason() +
                     ")"};
    if (std::string problem = truncationProblem(bytes); !problem.empty())
        return Error{name + ": " + problem};
    const int channels = comp <= 2 ? 1 : 3;
    const bool sixteen = stbi_is_16_bit_from_memory(bytes.data(), len);
    Image image(w, h, channels, sixteen ? 16 : 8);
    int fw = 0, fh = 0, fc = 0;
    if (sixteen) {
        std::unique_ptr<stbi_us, void (*)(void*)> data(
            stbi_load_16_from_memory(bytes.data(), len, &fw, &fh, &fc, channels), stbi_image_free);
        if (!data) return Error{name + ": corrupt image (" + stbi_failure_reason() + ")"};
        for (std::size_t i = 0; i < image.samples.size(); ++i)
            image.samples[i] = static_cast<float>(data.get()[i]) / 65535.f;
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> data(
            stbi_load_from_memory(bytes.data(), len, &fw, &fh, &fc, channels), stbi_image_free);
        if (!data) return Error{name + ": corrupt image (" + stbi_failure_reason() + ")"};
        for (std::size_t i = 0; i < image.samples.size(); ++i)
            image.samples[i] = static_cast<float>(data.get()[i]) / 255.f;
    }
    return image;
}

Result<Image> loadImage(const std::string& path) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    return decodeImage(*bytes, path);
}

Result<Mask> loadMask(const std::string& path, int width, int height) {
    Result<Image> image = loadImage(path);
    if (!image) return Error{image.error()};
    if (image->width != width || image->height != height)
        return Error{path + ": mask is " + std::to_string(image->width) + "x" +
                     std::to_string(image->height) + " but the images are " +
                     std::to_string(width) + "x" + std::to_string(height)};
    Mask mask{width, height, std::vector<std::uint8_t>(image->pixelCount())};
    for (std::size_t i = 0; i < mask.inside.size(); ++i)
        for (int c = 0; c < image->channels; ++c)
            if (image->samples[i * image->channels + c] > 0) mask.inside[i] = 1;
    if (mask.count() == 0) return Error{path + ": mask has no sample pixels (all zero)"};
    return mask;
}

Mask fullMask(int width, int height) {
    return {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, 1)};
}

Bytes encodePng(const Image& image, int bitDepth) {
    BTFLUT_CHECK(bitDepth == 8 || bitDepth == 16);
    BTFLUT_CHECK(image.channels == 1 || image.channels == 3);
    const double scale = bitDepth == 16 ? 65535.0 : 255.0;
    auto code = [scale](float v) {
        return std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * scale);
    };
    std::vector<std::uint8_t> raw8;
    std::vector<std::uint16_t> raw16;
    if (bitDepth == 8) {
        raw8.resize(image.samples.size());
        for (std::size_t i = 0; i < raw8.size(); ++i)
            raw8[i] = static_cast<std::uint8_t>(code(image.samples[i]));
    } else {
        raw16.resize(image.samples.size());
        for (std::size_t i = 0; i < raw16.size(); ++i)
            raw16[i] = static_cast<std::uint16_t>(code(image.samples[i]));
    }
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> ctx(spng_ctx_new(SPNG_CTX_ENCODER),
                                                       spng_ctx_free);
    BTFLUT_CHECK(ctx);
    spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
    spng_ihdr ihdr{};
    ihdr.width = static_cast<std::uint32_t>(image.width);
    ihdr.height = static_cast<std::uint32_t>(image.height);
    ihdr.bit_depth = static_cast<std::uint8_t>(bitDepth);
    ihdr.color_type = image.channels == 1 ? SPNG_COLOR_TYPE_GRAYSCALE : SPNG_COLOR_TYPE_TRUECOLOR;
    BTFLUT_CHECK(spng_set_ihdr(ctx.get(), &ihdr) == 0);
    const void* raw = bitDepth == 8 ? static_cast<const void*>(raw8.data()) : raw16.data();
    std::size_t rawSize = bitDepth == 8 ? raw8.size() : raw16.size() * 2;
    int err = spng_encode_image(ctx.get(), raw, rawSize, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    BTFLUT_CHECK(err == 0);
    std::size_t pngSize = 0;
    std::unique_ptr<void, void (*)(void*)> png(spng_get_png_buffer(ctx.get(), &pngSize, &err),
                                               std::free);
    BTFLUT_CHECK(png && err == 0);
    const auto* p = static_cast<const std::uint8_t*>(png.get());
    return Bytes(p, p + pngSize);
}

Status savePng(const Image& image, const std::string& path, int bitDepth) {
    return writeFileAtomically(path, encodePng(image, bitDepth));
}

}  // namespace btflut
