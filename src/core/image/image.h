#pragma once
// Images as float samples in [0, 1] (0 = black, 1 = white), and sample masks.
//
//   Result<Image> img = loadImage("rock.3.tga");   // PNG (8/16-bit), JPEG, TGA, BMP
//   float g = img->grey(x, row);                     // mean of R, G, B (the paper's grey)
//   Status s = savePng(*img, "out.png", 16);         // atomic write, 8 or 16 bits
//
// Rows are stored top row first, as in the files (image y points up, so row 0 is the
// largest y). Alpha is dropped; grey-alpha loads as grey.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/io/file_io.h"
#include "core/result.h"

namespace btflut {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;            ///< 1 (grey) or 3 (RGB)
    int bitDepth = 8;            ///< precision of the source: 8 or 16 bits per sample
    std::vector<float> samples;  ///< width * height * channels, interleaved

    Image() = default;
    Image(int w, int h, int c, int depth = 8)
        : width(w), height(h), channels(c), bitDepth(depth), samples(static_cast<std::size_t>(w) * h * c, 0.f) {}

    std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
    float& at(int x, int row, int c) { return samples[(static_cast<std::size_t>(row) * width + x) * channels + c]; }
    float at(int x, int row, int c) const {
        return samples[(static_cast<std::size_t>(row) * width + x) * channels + c];
    }
    /// Grey value of pixel i: the mean of R, G and B.
    float grey(std::size_t i) const {
        const float* p = &samples[i * channels];
        return channels == 1 ? p[0] : (p[0] + p[1] + p[2]) * (1.f / 3.f);
    }
    /// Largest integer sample value of the source precision (255 or 65535).
    int maxCode() const { return bitDepth == 16 ? 65535 : 255; }
};

/// An image as the integer codes its file holds, before any conversion to floats: what
/// exact comparisons want (`btflut compare`), at a quarter (8 bits) or half (16) of the memory of an Image.
struct ImageCodes {
    int width = 0;
    int height = 0;
    int channels = 0;  ///< 1 (grey) or 3 (RGB)
    int bitDepth = 8;  ///< 8: one byte per sample; 16: two, in host order
    int stride = 0;    ///< samples from one pixel to the next (more than `channels` where alpha is kept)
    std::unique_ptr<std::uint8_t[]> bytes;

    std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
    int maxCode() const { return bitDepth == 16 ? 65535 : 255; }
    const std::uint8_t* eight() const { return bytes.get(); }
    const std::uint16_t* sixteen() const { return reinterpret_cast<const std::uint16_t*>(bytes.get()); }
};

/// Sample mask: one byte per pixel, non-zero = part of the sample.
struct Mask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> inside;

    std::size_t count() const;
};

/// A rectangle of pixels, rows top first.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool operator==(const PixelRect&) const = default;
};

/// The largest axis-aligned rectangle of pixels all inside the mask (by area; the first such
/// from the top left); empty for an empty mask. A surface wrapped with it shows the sample and
/// none of its background.
PixelRect largestRectInside(const Mask& mask);

/// The default of maxImagePixels(): 2^28 pixels (16384 x 16384). A decoded image takes
/// 4 bytes per sample (12 per RGB pixel), plus the decoder's buffer while decoding.
constexpr std::uint64_t kDefaultMaxImagePixels = std::uint64_t{1} << 28;

/// The most pixels an image file may declare; larger ones are refused from their header,
/// before anything is allocated. Process-wide (`btflut --max-pixels N`).
std::uint64_t maxImagePixels();
void setMaxImagePixels(std::uint64_t pixels);

/// Refuses a width x height (of something named `name`) that is empty or over
/// maxImagePixels(), with the error decoders give.
Status checkImageSize(std::uint64_t width, std::uint64_t height, const std::string& name);

/// Decodes an image file. Errors name the file and say what is wrong (missing, unknown
/// format, corrupt, truncated, over the pixel limit).
Result<Image> loadImage(const std::string& path);

/// Decodes an image held in memory; `name` is used in error messages. With an expected
/// size, a file declaring another is refused from its header, before decoding.
Result<Image> decodeImage(const Bytes& bytes, const std::string& name, int expectedWidth = 0, int expectedHeight = 0);

/// Decodes an image file (or bytes) into its codes; the same checks and errors as loadImage.
Result<ImageCodes> loadImageCodes(const std::string& path);
Result<ImageCodes> decodeImageCodes(const Bytes& bytes, const std::string& name, int expectedWidth = 0,
                                    int expectedHeight = 0);

/// Codes as floats (code / max code), and floats as the nearest codes of `bitDepth` (8 or 16)
/// bits (clamped to [0, 1]; NaN to 0).
Image toImage(const ImageCodes& codes);
ImageCodes toCodes(const Image& image, int bitDepth);

/// A mask from an image file (non-zero in any channel = sample). It must be
/// `width` x `height` and contain at least one sample pixel.
Result<Mask> loadMask(const std::string& path, int width, int height);

/// A mask with every pixel inside.
Mask fullMask(int width, int height);

/// Bytes per texel (a mask as 0/1, region labels) as an 8-bit grey image of value
/// byte * scale / 255, for files.
Image byteImage(const std::vector<std::uint8_t>& bytes, int width, int height, int scale);

/// PNG bytes of an image at 8 or 16 bits per sample (values clamped to [0, 1]); grey, RGB or RGBA.
Bytes encodePng(const Image& image, int bitDepth);

/// Writes a PNG atomically.
Status savePng(const Image& image, const std::string& path, int bitDepth = 8);

}  // namespace btflut
