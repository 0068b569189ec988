// The only place that sees the decoders (libspng for PNG, libjpeg-turbo for JPEG, stb_image
// for TGA and BMP) and the PNG encoder: the rest of btflut gets owning Image values.
//
// Every decoder is given the image's size from its header first, so a file that claims
// more pixels than maxImagePixels() is refused before anything is allocated, and the
// formats whose decoders fill missing data with zeros (stb's TGA and BMP) are checked for
// truncation before decoding.
#include "core/image/image.h"

#include <spng.h>
#include <turbojpeg.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO  // every read goes through readFile, so errors name the file
#define STBI_FAILURE_USERMSG
#define STBI_ONLY_TGA  // PNG and JPEG go to maintained decoders (libspng, libjpeg-turbo)
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

std::atomic<std::uint64_t> g_maxPixels{kDefaultMaxImagePixels};

std::uint32_t le16(const Bytes& b, std::size_t at) { return b[at] | (b[at + 1] << 8); }
std::uint32_t le32(const Bytes& b, std::size_t at) {
    return le16(b, at) | (static_cast<std::uint32_t>(le16(b, at + 2)) << 16);
}

enum class Format { Png, Jpeg, Bmp, Tga };

Format formatOf(const Bytes& b) {
    if (b.size() >= 8 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G') return Format::Png;
    if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return Format::Jpeg;
    if (b.size() >= 2 && b[0] == 'B' && b[1] == 'M') return Format::Bmp;
    return Format::Tga;  // the one format without a magic number
}

// What a caller knows before decoding: the name for errors and, where it is known, the size.
struct Request {
    const std::string& name;
    int width = 0, height = 0;  ///< 0: any
};

std::string sizeText(std::uint64_t width, std::uint64_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// The pixel limit and the expected size, checked from a header before any allocation.
Status checkSize(std::uint64_t width, std::uint64_t height, const Request& r) {
    if (width == 0 || height == 0) return Error{r.name + ": image has no pixels (" + sizeText(width, height) + ")"};
    const std::uint64_t limit = maxImagePixels();
    if (width > limit || height > limit || width * height > limit)
        return Error{r.name + ": image is " + sizeText(width, height) + " pixels, over the limit of " +
                     std::to_string(limit) + " pixels (raise it with --max-pixels)"};
    if (r.width > 0 && (width != static_cast<std::uint64_t>(r.width) || height != static_cast<std::uint64_t>(r.height)))
        return Error{r.name + ": image is " + sizeText(width, height) + ", expected " +
                     sizeText(static_cast<std::uint64_t>(r.width), static_cast<std::uint64_t>(r.height))};
    return success();
}

// Whether a PNG without an alpha channel marks a colour transparent (a tRNS chunk).
bool hasTransparency(spng_ctx* ctx) {
    spng_trns trns{};
    return spng_get_trns(ctx, &trns) == 0;
}

Result<ImageCodes> decodePng(const Bytes& b, const Request& r) {
    const std::string& name = r.name;
    // libspng checks chunk CRCs, but stops at the end of the image data: a cut in the
    // final IEND chunk is caught here.
    bool complete = false;
    for (std::size_t i = b.size() >= 12 ? b.size() - 12 : 0; i + 8 <= b.size(); ++i)
        complete = complete || std::memcmp(&b[i], "IEND", 4) == 0;
    if (!complete) return Error{name + ": truncated PNG (no complete IEND chunk)"};
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> ctx(spng_ctx_new(kFuzzingBuild ? SPNG_CTX_IGNORE_ADLER32 : 0),
                                                       spng_ctx_free);
    if (!ctx) return Error{name + ": out of memory"};
    if (kFuzzingBuild) spng_set_crc_action(ctx.get(), SPNG_CRC_USE, SPNG_CRC_USE);
    auto fail = [&](int code) { return Error{name + ": corrupt PNG (" + spng_strerror(code) + ")"}; };
    spng_set_chunk_limits(ctx.get(), 1u << 26, 1u << 26);  // ancillary chunks (text, ICC) up to 64 MiB
    spng_set_png_buffer(ctx.get(), b.data(), b.size());
    spng_ihdr ihdr{};
    if (int e = spng_get_ihdr(ctx.get(), &ihdr)) return fail(e);
    if (Status s = checkSize(ihdr.width, ihdr.height, r); !s) return Error{s.error()};
    const bool grey =
        ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE || ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE_ALPHA;
    const bool sixteen = ihdr.bit_depth == 16;
    int format = 0, stride = 0;
    if (grey && !sixteen)
        format = SPNG_FMT_GA8, stride = 2;
    else if (grey)
        format = SPNG_FMT_GA16, stride = 2;
    else if (!sixteen && ihdr.color_type != SPNG_COLOR_TYPE_TRUECOLOR_ALPHA && !hasTransparency(ctx.get()))
        format = SPNG_FMT_RGB8, stride = 3;
    else if (!sixteen)  // its alpha kept (compare holds it to the tolerance)
        format = SPNG_FMT_RGBA8, stride = 4;
    else
        format = SPNG_FMT_RGBA16, stride = 4;
    std::size_t size = 0;
    if (int e = spng_decoded_image_size(ctx.get(), format, &size)) return fail(e);
    // Left uninitialised: pages a failing decode never reaches are never touched.
    std::unique_ptr<std::uint8_t[]> pixels(new (std::nothrow) std::uint8_t[size]);
    if (!pixels)
        return Error{name + ": out of memory for a " + std::to_string(ihdr.width) + "x" + std::to_string(ihdr.height) +
                     " image"};
    if (int e = spng_decode_image(ctx.get(), pixels.get(), size, format, 0)) return fail(e);
    return ImageCodes{static_cast<int>(ihdr.width),
                      static_cast<int>(ihdr.height),
                      grey ? 1 : 3,
                      sixteen ? 16 : 8,
                      stride,
                      std::move(pixels)};
}

static_assert(sizeof(unsigned long) >= sizeof(std::size_t), "libjpeg-turbo takes the file length as unsigned long");

Result<ImageCodes> decodeJpeg(const Bytes& b, const Request& r) {
    const std::string& name = r.name;
    // The end-of-image marker must follow the last start-of-scan marker. Entropy-coded
    // data stuffs 0xFF as FF 00, so FF D9 there is a real marker.
    std::size_t lastScan = 0;
    for (std::size_t i = 2; i + 1 < b.size(); ++i)
        if (b[i] == 0xFF && b[i + 1] == 0xDA) lastScan = i;
    bool ended = false;
    for (std::size_t i = lastScan; i + 1 < b.size() && !ended; ++i) ended = b[i] == 0xFF && b[i + 1] == 0xD9;
    if (!ended) return Error{name + ": truncated JPEG (no end-of-image marker)"};
    std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), tjDestroy);
    if (!tj) return Error{name + ": cannot start the JPEG decoder"};
    auto fail = [&] { return Error{name + ": corrupt JPEG (" + std::string(tjGetErrorStr2(tj.get())) + ")"}; };
    int width = 0, height = 0, subsampling = 0, colourspace = 0;
    if (tjDecompressHeader3(tj.get(), b.data(), static_cast<unsigned long>(b.size()), &width, &height, &subsampling,
                            &colourspace) != 0)
        return fail();
    if (Status s = checkSize(static_cast<std::uint64_t>(std::max(width, 0)),
                             static_cast<std::uint64_t>(std::max(height, 0)), r);
        !s)
        return Error{s.error()};
    if (colourspace == TJCS_CMYK || colourspace == TJCS_YCCK)
        return Error{name + ": CMYK JPEG images are not supported (convert it to RGB)"};
    const int channels = colourspace == TJCS_GRAY ? 1 : 3;
    std::unique_ptr<std::uint8_t[]> pixels(new (std::nothrow)
                                               std::uint8_t[static_cast<std::size_t>(width) * height * channels]);
    if (!pixels)
        return Error{name + ": out of memory for a " + std::to_string(width) + "x" + std::to_string(height) + " image"};
    // A warning (a corrupt or cut stream) is an error, and a progressive image may have
    // at most 500 scans (a CPU bomb otherwise).
    if (tjDecompress2(tj.get(), b.data(), static_cast<unsigned long>(b.size()), pixels.get(), width, 0, height,
                      channels == 1 ? TJPF_GRAY : TJPF_RGB,
                      TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS | TJFLAG_ACCURATEDCT) != 0)
        return fail();
    return ImageCodes{width, height, channels, 8, channels, std::move(pixels)};
}

// stb_image fills zeros past the end of TGA and BMP pixel data, so their length is
// checked here; also the header's size, against the pixel limit.
Status checkBmp(const Bytes& b, const Request& r) {
    const std::string& name = r.name;
    const std::size_t n = b.size();
    if (n < 34) return Error{name + ": truncated BMP header"};
    const std::uint64_t offset = le32(b, 10);
    const auto w = static_cast<std::int32_t>(le32(b, 18)), h = static_cast<std::int32_t>(le32(b, 22));
    const std::uint64_t width = static_cast<std::uint64_t>(std::abs(static_cast<std::int64_t>(w)));
    const std::uint64_t height = static_cast<std::uint64_t>(std::abs(static_cast<std::int64_t>(h)));
    if (Status s = checkSize(width, height, r); !s) return s;
    const std::uint32_t bpp = le16(b, 28), compression = le32(b, 30);
    if (compression == 0 || compression == 3) {
        const std::uint64_t stride = ((width * bpp + 31) / 32) * 4;
        if (offset + stride * height > n) return Error{name + ": truncated BMP (pixel data ends early)"};
    }
    return success();
}

Status checkTga(const Bytes& b, const Request& r) {
    const std::string& name = r.name;
    const std::size_t n = b.size();
    if (n < 18) return Error{name + ": file too short to be an image"};
    const std::uint32_t type = b[2];
    if (Status s = checkSize(le16(b, 12), le16(b, 14), r); !s) return s;
    const std::uint64_t bytesPerPixel = (b[16] + 7u) / 8u;
    const std::uint64_t palette = b[1] ? le16(b, 5) * ((b[7] + 7u) / 8u) : 0;
    const std::uint64_t pixels = static_cast<std::uint64_t>(le16(b, 12)) * le16(b, 14);
    std::uint64_t at = 18 + b[0] + palette;
    if (type == 1 || type == 2 || type == 3) {
        if (at + pixels * bytesPerPixel > n) return Error{name + ": truncated TGA (pixel data ends early)"};
    } else if (type == 9 || type == 10 || type == 11) {
        // Run-length packets: a header byte, then one pixel (a run) or count pixels (raw).
        for (std::uint64_t done = 0; done < pixels;) {
            if (at >= n) return Error{name + ": truncated TGA (run-length data ends early)"};
            const std::uint32_t header = b[at++];
            const std::uint64_t count = (header & 0x7F) + 1u;
            at += (header & 0x80) ? bytesPerPixel : count * bytesPerPixel;
            done += count;
        }
        if (at > n) return Error{name + ": truncated TGA (run-length data ends early)"};
    }
    return success();
}

Result<ImageCodes> decodeWithStb(const Bytes& bytes, const Request& r, Format format) {
    const std::string& name = r.name;
    if (bytes.size() > static_cast<std::size_t>(INT32_MAX)) return Error{name + ": file too large"};
    const auto len = static_cast<int>(bytes.size());
    // BMP has a magic number, so its header is checked first; a TGA is only known to be
    // one once stb recognises its header (stbi_info allocates nothing).
    if (format == Format::Bmp)
        if (Status s = checkBmp(bytes, r); !s) return Error{s.error()};
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &comp))
        return Error{name + ": not a readable PNG/JPEG/TGA/BMP image (" + stbi_failure_reason() + ")"};
    if (format == Format::Tga)
        if (Status s = checkTga(bytes, r); !s) return Error{s.error()};
    const int channels = comp <= 2 ? 1 : 3;
    int fw = 0, fh = 0, fc = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load_from_memory(bytes.data(), len, &fw, &fh, &fc, channels),
                                                   stbi_image_free);
    if (!data) return Error{name + ": corrupt image (" + stbi_failure_reason() + ")"};
    // Copied into a buffer of our own (BMP and TGA only: rare and small).
    const std::size_t size = static_cast<std::size_t>(fw) * fh * channels;
    std::unique_ptr<std::uint8_t[]> pixels(new (std::nothrow) std::uint8_t[size]);
    if (!pixels) return Error{name + ": out of memory for a " + sizeText(fw, fh) + " image"};
    std::memcpy(pixels.get(), data.get(), size);
    return ImageCodes{fw, fh, channels, 8, channels, std::move(pixels)};
}

}  // namespace

std::uint64_t maxImagePixels() { return g_maxPixels.load(std::memory_order_relaxed); }
void setMaxImagePixels(std::uint64_t pixels) { g_maxPixels.store(pixels, std::memory_order_relaxed); }

Status checkImageSize(std::uint64_t width, std::uint64_t height, const std::string& name) {
    return checkSize(width, height, {name});
}

std::size_t Mask::count() const {
    return static_cast<std::size_t>(std::count_if(inside.begin(), inside.end(), [](std::uint8_t v) { return v != 0; }));
}

PixelRect largestRectInside(const Mask& mask) {
    // Row by row, the run of inside pixels above each column; the largest rectangle under that
    // histogram by a stack of rising heights (each bar's reach left and right), O(width x height).
    PixelRect best;
    std::vector<int> run(static_cast<std::size_t>(mask.width) + 1, 0), stack;
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x)
            run[static_cast<std::size_t>(x)] =
                mask.inside[static_cast<std::size_t>(y) * mask.width + x] ? run[static_cast<std::size_t>(x)] + 1 : 0;
        stack.clear();
        for (int x = 0; x <= mask.width; ++x) {  // run[width] stays 0: empties the stack
            while (!stack.empty() && run[static_cast<std::size_t>(stack.back())] >= run[static_cast<std::size_t>(x)]) {
                const int height = run[static_cast<std::size_t>(stack.back())];
                stack.pop_back();
                const int left = stack.empty() ? 0 : stack.back() + 1;
                if (static_cast<long>(height) * (x - left) > static_cast<long>(best.width) * best.height)
                    best = {left, y - height + 1, x - left, height};
            }
            stack.push_back(x);
        }
    }
    return best;
}

Result<ImageCodes> decodeImageCodes(const Bytes& bytes, const std::string& name, int expectedWidth,
                                    int expectedHeight) {
    if (bytes.empty()) return Error{name + ": empty file"};
    const Request request{name, expectedWidth, expectedHeight};
    switch (const Format format = formatOf(bytes)) {
        case Format::Png:
            return decodePng(bytes, request);
        case Format::Jpeg:
            return decodeJpeg(bytes, request);
        default:
            return decodeWithStb(bytes, request, format);
    }
}

Result<ImageCodes> loadImageCodes(const std::string& path) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    return decodeImageCodes(*bytes, path);
}

Image toImage(const ImageCodes& codes) {
    Image image(codes.width, codes.height, codes.channels, codes.bitDepth);
    const std::size_t n = image.pixelCount();
    const int channels = codes.channels, stride = codes.stride;
    float* out = image.samples.data();
    if (codes.bitDepth == 16) {
        const std::uint16_t* in = codes.sixteen();
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < channels; ++c) *out++ = static_cast<float>(in[i * stride + c]) / 65535.f;
    } else {
        const std::uint8_t* in = codes.eight();
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < channels; ++c) *out++ = static_cast<float>(in[i * stride + c]) / 255.f;
    }
    return image;
}

ImageCodes toCodes(const Image& image, int bitDepth) {
    BTFLUT_CHECK(bitDepth == 8 || bitDepth == 16);
    const std::size_t n = image.samples.size();
    ImageCodes codes{image.width,    image.height,
                     image.channels, bitDepth,
                     image.channels, std::make_unique_for_overwrite<std::uint8_t[]>(n * (bitDepth == 16 ? 2 : 1))};
    // Each sample to the nearest code; NaN and below 0 to 0, above 1 to the top code.
    auto code = [](float v, float top) { return static_cast<int>((v >= 0.f ? std::min(v, 1.f) : 0.f) * top + 0.5f); };
    if (bitDepth == 16) {
        auto* out = reinterpret_cast<std::uint16_t*>(codes.bytes.get());
        for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint16_t>(code(image.samples[i], 65535.f));
    } else {
        for (std::size_t i = 0; i < n; ++i) codes.bytes[i] = static_cast<std::uint8_t>(code(image.samples[i], 255.f));
    }
    return codes;
}

Result<Image> decodeImage(const Bytes& bytes, const std::string& name, int expectedWidth, int expectedHeight) {
    Result<ImageCodes> codes = decodeImageCodes(bytes, name, expectedWidth, expectedHeight);
    if (!codes) return Error{codes.error()};
    return toImage(*codes);
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
        return Error{path + ": mask is " + std::to_string(image->width) + "x" + std::to_string(image->height) +
                     " but the images are " + std::to_string(width) + "x" + std::to_string(height)};
    Mask mask{width, height, std::vector<std::uint8_t>(image->pixelCount())};
    for (std::size_t i = 0; i < mask.inside.size(); ++i)
        for (int c = 0; c < image->channels; ++c)
            if (image->samples[i * image->channels + c] > 0) mask.inside[i] = 1;
    if (mask.count() == 0) return Error{path + ": mask has no sample pixels (all zero)"};
    return mask;
}

Image byteImage(const std::vector<std::uint8_t>& bytes, int width, int height, int scale) {
    BTFLUT_CHECK(bytes.size() == static_cast<std::size_t>(width) * height);
    Image image(width, height, 1);
    for (std::size_t i = 0; i < bytes.size(); ++i) image.samples[i] = static_cast<float>(bytes[i] * scale) / 255.f;
    return image;
}

Mask fullMask(int width, int height) {
    return {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, 1)};
}

Bytes encodePng(const Image& image, int bitDepth) {
    BTFLUT_CHECK(bitDepth == 8 || bitDepth == 16);
    BTFLUT_CHECK(image.channels == 1 || image.channels == 3 || image.channels == 4);
    const double scale = bitDepth == 16 ? 65535.0 : 255.0;
    auto code = [scale](float v) { return std::lround(std::clamp(static_cast<double>(v), 0.0, 1.0) * scale); };
    std::vector<std::uint8_t> raw8;
    std::vector<std::uint16_t> raw16;
    if (bitDepth == 8) {
        raw8.resize(image.samples.size());
        for (std::size_t i = 0; i < raw8.size(); ++i) raw8[i] = static_cast<std::uint8_t>(code(image.samples[i]));
    } else {
        raw16.resize(image.samples.size());
        for (std::size_t i = 0; i < raw16.size(); ++i) raw16[i] = static_cast<std::uint16_t>(code(image.samples[i]));
    }
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> ctx(spng_ctx_new(SPNG_CTX_ENCODER), spng_ctx_free);
    BTFLUT_CHECK(ctx);
    spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
    spng_ihdr ihdr{};
    ihdr.width = static_cast<std::uint32_t>(image.width);
    ihdr.height = static_cast<std::uint32_t>(image.height);
    ihdr.bit_depth = static_cast<std::uint8_t>(bitDepth);
    ihdr.color_type = image.channels == 1   ? SPNG_COLOR_TYPE_GRAYSCALE
                      : image.channels == 3 ? SPNG_COLOR_TYPE_TRUECOLOR
                                            : SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
    BTFLUT_CHECK(spng_set_ihdr(ctx.get(), &ihdr) == 0);
    const void* raw = bitDepth == 8 ? static_cast<const void*>(raw8.data()) : raw16.data();
    std::size_t rawSize = bitDepth == 8 ? raw8.size() : raw16.size() * 2;
    int err = spng_encode_image(ctx.get(), raw, rawSize, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    BTFLUT_CHECK(err == 0);
    std::size_t pngSize = 0;
    std::unique_ptr<void, void (*)(void*)> png(spng_get_png_buffer(ctx.get(), &pngSize, &err), std::free);
    BTFLUT_CHECK(png && err == 0);
    const auto* p = static_cast<const std::uint8_t*>(png.get());
    return Bytes(p, p + pngSize);
}

Status savePng(const Image& image, const std::string& path, int bitDepth) {
    return writeFileAtomically(path, encodePng(image, bitDepth));
}

}  // namespace btflut
