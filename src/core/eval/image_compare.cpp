// btflut compare's figures (image_compare.h).
#include "core/eval/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "core/check.h"
#include "core/image/canvas.h"
#include "core/parallel.h"

namespace btflut {

namespace {

// p99 and pixels from the codes of two images of one bit depth, in bands of rows in parallel
// (a histogram of the differences: no float image, no sort; `compare` stays within its time).
void countPixels(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold, CompareFigures& f) {
    BTFLUT_CHECK(a.bitDepth == b.bitDepth && a.channels == b.channels);
    const int top = b.maxCode(), channels = b.channels;
    const double limit = threshold * top / 255.0;  // in codes
    constexpr int kBand = 64;
    const auto bands = static_cast<std::size_t>((b.height + kBand - 1) / kBand);
    std::vector<std::vector<std::uint32_t>> histograms(bands);
    std::vector<std::size_t> pixels(bands, 0), over(bands, 0);
    // One band's rows, for the samples' type (8- or 16-bit codes) and channel count. Four
    // histograms taken in turn, so that equal differences in a row (mostly 0) do not wait on
    // each other's increments; no mask test when every pixel is compared.
    const bool everyPixel = mask.count() == b.pixelCount();
    auto count = [&]<int C>(std::size_t band, const auto* pa, const auto* pb) {
        const std::size_t bins = static_cast<std::size_t>(top) + 1;
        std::vector<std::uint32_t> h(4 * bins, 0);
        const auto sa = static_cast<std::size_t>(a.stride), sb = static_cast<std::size_t>(b.stride);
        const std::size_t first = band * kBand * static_cast<std::size_t>(b.width),
                          last = std::min(b.pixelCount(), (band + 1) * kBand * static_cast<std::size_t>(b.width));
        std::size_t counted = 0, beyond = 0;
        for (std::size_t i = first; i < last; ++i) {
            if (!everyPixel && !mask.inside[i]) continue;
            int worst = 0;
            for (int c = 0; c < C; ++c) {
                const int d = std::abs(int{pa[i * sa + static_cast<std::size_t>(c)]} -
                                       int{pb[i * sb + static_cast<std::size_t>(c)]});
                ++h[static_cast<std::size_t>((i + static_cast<std::size_t>(c)) & 3u) * bins +
                    static_cast<std::size_t>(d)];
                worst = std::max(worst, d);
            }
            ++counted;
            beyond += worst > limit + 1e-9;
        }
        histograms[band].assign(bins, 0);
        for (std::size_t k = 0; k < 4; ++k)
            for (std::size_t d = 0; d < bins; ++d) histograms[band][d] += h[k * bins + d];
        pixels[band] = counted, over[band] = beyond;
    };
    parallelFor(bands, 0, [&](std::size_t band) {
        if (b.bitDepth == 16) {
            if (channels == 3)
                count.template operator()<3>(band, a.sixteen(), b.sixteen());
            else
                count.template operator()<1>(band, a.sixteen(), b.sixteen());
        } else {
            if (channels == 3)
                count.template operator()<3>(band, a.eight(), b.eight());
            else
                count.template operator()<1>(band, a.eight(), b.eight());
        }
    });
    std::vector<std::uint64_t> total(static_cast<std::size_t>(top) + 1, 0);
    std::size_t samples = 0, pixelCount = 0, overCount = 0;
    for (std::size_t band = 0; band < bands; ++band) {
        for (std::size_t d = 0; d < total.size(); ++d) total[d] += histograms[band][d];
        pixelCount += pixels[band], overCount += over[band];
    }
    for (std::uint64_t n : total) samples += n;
    if (samples == 0) return;
    // The sample at index floor(0.99 (n - 1)) of the sorted differences.
    const auto index = static_cast<std::uint64_t>(0.99 * static_cast<double>(samples - 1));
    std::uint64_t seen = 0;
    std::size_t d = 0;
    while (d < total.size() && (seen += total[d]) <= index) ++d;
    f.p99 = static_cast<double>(d) * 255.0 / top;
    f.pixels = 100.0 * static_cast<double>(overCount) / static_cast<double>(pixelCount);
}

// A grey image as RGB, its grey in all three channels: so grey and RGB renders compare.
ImageCodes asRgb(const ImageCodes& grey) {
    ImageCodes out;
    out.width = grey.width;
    out.height = grey.height;
    out.channels = out.stride = 3;
    out.bitDepth = grey.bitDepth;
    const std::size_t bytes = static_cast<std::size_t>(grey.bitDepth / 8);
    out.bytes = std::make_unique<std::uint8_t[]>(grey.pixelCount() * 3 * bytes);
    for (std::size_t i = 0; i < grey.pixelCount(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            std::memcpy(&out.bytes[(i * 3 + c) * bytes], &grey.bytes[i * static_cast<std::size_t>(grey.stride) * bytes],
                        bytes);
    return out;
}

// A pixel's alpha in [0, 1]: the stored one, or opaque where the file keeps none.
std::vector<float> alphaOf(const ImageCodes& image) {
    std::vector<float> alpha(image.pixelCount(), 1.f);
    if (image.stride == image.channels) return alpha;
    const auto stride = static_cast<std::size_t>(image.stride), at = static_cast<std::size_t>(image.channels);
    for (std::size_t i = 0; i < alpha.size(); ++i)
        alpha[i] = image.bitDepth == 16 ? static_cast<float>(image.sixteen()[i * stride + at]) / 65535.f
                                        : static_cast<float>(image.eight()[i * stride + at]) / 255.f;
    return alpha;
}

}  // namespace

double figure(const CompareFigures& f, const std::string& name) {
    const ImageErrors& e = f.e;
    if (name == "p99") return f.p99;
    if (name == "pixels") return f.pixels;
    if (name == "psnr") return f.identical() ? INFINITY : e.psnr;
    if (name == "ssim") return e.ssim;
    if (name == "max") return e.maxDifference * 255;
    if (name == "mean") return e.meanDifference * 255;
    if (name == "l1") return e.l1;
    return e.emd;
}

bool within(const CompareFigures& f, const Bound& b) {
    const double v = figure(f, b.name);
    return b.name == "psnr" || b.name == "ssim" ? v >= b.limit : v <= b.limit;
}

Image differenceImage(const Image& a, const Image& b, const Mask& mask, double full) {
    Image out(b.width, b.height, 3);
    for (std::size_t i = 0; i < b.pixelCount(); ++i) {
        float* rgb = &out.samples[i * 3];
        if (!mask.inside[i]) {
            rgb[0] = 0.05f, rgb[1] = 0.05f, rgb[2] = 0.2f;
            continue;
        }
        double worst = 0;
        for (int c = 0; c < b.channels; ++c)
            worst = std::max(
                worst, std::abs(static_cast<double>(a.samples[i * a.channels + c]) - b.samples[i * b.channels + c]));
        const float base = 0.3f * b.grey(i);
        rgb[0] = rgb[1] = rgb[2] = base;
        if (worst > 0.5 / 65535) {
            rgb[0] = static_cast<float>(std::clamp(worst * 255 / full, 0.25, 1.0));
            rgb[1] = rgb[2] = 0;
        }
    }
    return out;
}

Image sideBySide(const Image& actual, const Image& expected, const Image& difference) {
    const int w = expected.width, strip = Canvas::kTextHeight + 6;
    Canvas canvas(3 * w, strip + expected.height);
    const Image* panes[3] = {&expected, &actual, &difference};
    const char* names[3] = {"expected", "actual", "difference"};
    for (int k = 0; k < 3; ++k) {
        Image pane(panes[k]->width, panes[k]->height, 3);  // 16-bit and grey panes as RGB in [0, 1]
        for (std::size_t i = 0; i < pane.pixelCount(); ++i)
            for (int c = 0; c < 3; ++c)
                pane.samples[i * 3 + static_cast<std::size_t>(c)] =
                    panes[k]->samples[i * static_cast<std::size_t>(panes[k]->channels) +
                                      static_cast<std::size_t>(std::min(c, panes[k]->channels - 1))];
        canvas.blit(k * w, strip, pane);
        canvas.text(k * w + 4, 3, Canvas::fitted(names[k], w - 8), kInk);
    }
    return canvas.take();
}

void alphaFigures(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold, CompareFigures& f) {
    f.alpha = a.stride > a.channels || b.stride > b.channels;
    if (!f.alpha) return;
    const std::vector<float> alphaA = alphaOf(a), alphaB = alphaOf(b);
    std::size_t over = 0;
    for (std::size_t i = 0; i < alphaA.size(); ++i) {
        if (!mask.inside[i]) continue;
        const double d = std::abs(static_cast<double>(alphaA[i]) - alphaB[i]) * 255;
        f.alphaMax = std::max(f.alphaMax, d);
        over += d > threshold;
    }
    f.alphaPixels = 100.0 * static_cast<double>(over) / static_cast<double>(std::max<std::size_t>(1, mask.count()));
}

bool alphaWithin(const CompareFigures& f, const Tolerance& t) {
    double limit = t.threshold;
    for (const Bound& bound : t.bounds)
        if (bound.name == "max") limit = bound.limit;
    return !f.alpha || f.alphaMax <= limit + 1e-9;
}

void makeComparable(ImageCodes& a, ImageCodes& b) {
    if (a.channels == 1 && b.channels == 3) a = asRgb(a);
    if (a.channels == 3 && b.channels == 1) b = asRgb(b);
}

void differenceFigures(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold,
                       CompareFigures& f) {
    f.e = compareCodes(a, b, mask);
    if (a.bitDepth == b.bitDepth)
        countPixels(a, b, mask, threshold, f);
    else
        countPixels(toCodes(toImage(a), b.bitDepth), b, mask, threshold, f);  // as compareCodes recodes it
}

ImageCodes cropped(const ImageCodes& image, int x, int y, int width, int height) {
    ImageCodes out;
    out.width = width;
    out.height = height;
    out.channels = image.channels;
    out.bitDepth = image.bitDepth;
    out.stride = image.stride;
    const std::size_t bytes = static_cast<std::size_t>(image.stride) * (image.bitDepth / 8), row = bytes * width;
    out.bytes = std::make_unique<std::uint8_t[]>(row * static_cast<std::size_t>(height));
    for (int r = 0; r < height; ++r)
        std::memcpy(&out.bytes[row * static_cast<std::size_t>(r)],
                    &image.bytes[(static_cast<std::size_t>(y + r) * image.width + x) * bytes], row);
    return out;
}

}  // namespace btflut
