#include "core/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "core/histogram/histogram.h"
#include "core/parallel.h"

namespace btflut {

namespace {

constexpr int kRadius = 5;  // SSIM's Gaussian window: sigma 1.5, 11 taps
constexpr int kTaps = 2 * kRadius + 1;

struct SsimKernel {
    float weights[kTaps];
    SsimKernel() {
        double raw[kTaps], sum = 0;
        for (int k = -kRadius; k <= kRadius; ++k) sum += raw[k + kRadius] = std::exp(-0.5 * k * k / (1.5 * 1.5));
        for (int k = 0; k < kTaps; ++k) weights[k] = static_cast<float>(raw[k] / sum);
    }
};

// The horizontal Gaussian sums of x, y, xx, yy and xy along one row (edges clamped), into
// `out` (5 planes of w). `padded` is scratch of 5 * (w + 2 * kRadius) floats. Written as
// plain loops over the columns so that the compiler vectorises them (with AVX2 where the
// processor has it: the same arithmetic, element by element, so the same result).
[[gnu::target_clones("avx2", "default")]] void horizontalSums(const float* x, const float* y, int w, const float* g,
                                                              float* padded, float* out) {
    const int pw = w + 2 * kRadius;
    float* px = padded;
    float* py = padded + pw;
    for (int c = 0; c < pw; ++c) {
        const int at = std::clamp(c - kRadius, 0, w - 1);
        px[c] = x[at], py[c] = y[at];
    }
    float* pxx = padded + 2 * pw;
    float* pyy = padded + 3 * pw;
    float* pxy = padded + 4 * pw;
    for (int c = 0; c < pw; ++c) pxx[c] = px[c] * px[c], pyy[c] = py[c] * py[c], pxy[c] = px[c] * py[c];
    for (int m = 0; m < 5; ++m) {
        const float* in = padded + m * pw;
        float* o = out + m * w;
        for (int c = 0; c < w; ++c) o[c] = g[0] * in[c];
        for (int k = 1; k < kTaps; ++k)
            for (int c = 0; c < w; ++c) o[c] += g[k] * in[c + k];
    }
}

// The sum of SSIM over one row's mask pixels, from the ring of the horizontal sums of 11
// rows (the first of the window at slot `oldest`), with `s` scratch of 6 * w floats.
[[gnu::target_clones("avx2", "default")]] double ssimRow(const float* ring, int oldest, std::size_t w, const float* g,
                                                         const std::uint8_t* inside, float* s) {
    std::fill(s, s + 5 * w, 0.f);
    for (int k = 0; k < kTaps; ++k) {
        const float* in = ring + static_cast<std::size_t>((oldest + k) % kTaps) * 5 * w;
        for (std::size_t i = 0; i < 5 * w; ++i) s[i] += g[k] * in[i];
    }
    // The SSIM term of every column (vectorised), then its sum over the mask in four
    // independent partial sums (a fixed order: the same result every time).
    constexpr float c1 = 0.01f * 0.01f, c2 = 0.03f * 0.03f;
    float* term = s + 5 * w;
    for (std::size_t c = 0; c < w; ++c) {
        const float mx = s[c], my = s[w + c];
        const float vx = s[2 * w + c] - mx * mx, vy = s[3 * w + c] - my * my, cxy = s[4 * w + c] - mx * my;
        const float value = (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
        term[c] = inside[c] ? value : 0.f;
    }
    double partial[4] = {0, 0, 0, 0};
    std::size_t c = 0;
    for (; c + 4 <= w; c += 4)
        for (int k = 0; k < 4; ++k) partial[k] += term[c + k];
    for (; c < w; ++c) partial[0] += term[c];
    return (partial[0] + partial[1]) + (partial[2] + partial[3]);
}

// One image's codes of one type (8 or 16 bits) as the pass below reads them.
template <typename T>
struct CodeView {
    const T* samples;
    int channels, stride;
    float greyScale;                  // grey value of a sum of channel codes
    std::vector<std::uint8_t> binOf;  // histogram bin (of 64) of each sum of channel codes

    const T* pixel(std::size_t i) const { return samples + i * stride; }
    // The sums of the channels' codes of `w` pixels from pixel `at` (the common layouts
    // spelled out so that the compiler vectorises each).
    void greyRow(std::size_t at, std::size_t w, std::uint32_t* out) const {
        const T* s = pixel(at);
        auto sum = [&](auto step, auto count) {
            for (std::size_t i = 0; i < w; ++i)
                out[i] = count == 1 ? s[i * step] : std::uint32_t{s[i * step]} + s[i * step + 1] + s[i * step + 2];
        };
        if (channels == 3 && stride == 3)
            return sum(std::integral_constant<int, 3>{}, std::integral_constant<int, 3>{});
        if (channels == 3) return sum(std::integral_constant<int, 4>{}, std::integral_constant<int, 3>{});
        if (stride == 1) return sum(std::integral_constant<int, 1>{}, std::integral_constant<int, 1>{});
        return sum(std::integral_constant<int, 2>{}, std::integral_constant<int, 1>{});
    }
};

template <typename T>
CodeView<T> viewOf(const ImageCodes& c, const T* samples) {
    BTFLUT_CHECK((c.channels == 3 && (c.stride == 3 || c.stride == 4)) ||
                 (c.channels == 1 && (c.stride == 1 || c.stride == 2)));
    const auto last = static_cast<std::uint64_t>(c.channels) * static_cast<std::uint64_t>(c.maxCode());
    std::vector<std::uint8_t> bins(last + 1);
    for (std::uint64_t k = 0; k <= last; ++k)
        bins[k] = static_cast<std::uint8_t>(std::min<std::uint64_t>(k * 64 / last, 63));  // as binHistogram
    return {samples, c.channels, c.stride, static_cast<float>(1.0 / static_cast<double>(last)), std::move(bins)};
}

// What one band of rows adds to the figures; bands are added in order, so the result does
// not depend on the threads.
struct BandSums {
    double squared = 0, absolute = 0, worst = 0;   // in codes
    std::uint64_t pixels = 0;                      // pixels compared
    std::uint64_t binsP[64] = {}, binsQ[64] = {};  // grey histograms, 64 bins
    double ssim = 0;
};

// Every figure in one pass over bands of rows, in parallel: the differences and histograms
// of the band's rows, and SSIM (Wang et al. 2004: Gaussian windows of x, y, xx, yy and xy,
// sigma 1.5, radius 5, edges clamped, of the grey images). Within a band the horizontal sums
// of the last 11 rows stay in a ring that fits the cache and each output row is their
// vertical sum: no image-sized buffer is made.
template <typename T>
ImageErrors compareViews(const CodeView<T>& p, const CodeView<T>& q, int w, int h, double maxCode, const Mask& mask) {
    static const SsimKernel kernel;
    const float* g = kernel.weights;
    constexpr int kBand = 64;
    const auto plane = static_cast<std::size_t>(w);
    const int bands = (h + kBand - 1) / kBand;
    std::vector<BandSums> sums(static_cast<std::size_t>(bands));
    parallelFor(sums.size(), 0, [&](std::size_t band) {
        BandSums& out = sums[band];
        const int first = static_cast<int>(band) * kBand, last = std::min(h, first + kBand);
        std::vector<float> ring(kTaps * 5 * plane), padded(5 * (plane + 2 * kRadius)), s(6 * plane);
        std::vector<float> x(plane), y(plane);
        std::vector<std::uint32_t> greyP(plane), greyQ(plane);
        auto slot = [&](int row) { return &ring[static_cast<std::size_t>((row - first + kTaps) % kTaps) * 5 * plane]; };
        for (int row = first - kRadius; row < last + kRadius; ++row) {
            const std::size_t at = static_cast<std::size_t>(std::clamp(row, 0, h - 1)) * plane;
            p.greyRow(at, plane, greyP.data());
            q.greyRow(at, plane, greyQ.data());
            for (std::size_t c = 0; c < plane; ++c)
                x[c] = static_cast<float>(greyP[c]) * p.greyScale, y[c] = static_cast<float>(greyQ[c]) * q.greyScale;
            horizontalSums(x.data(), y.data(), w, g, padded.data(), slot(row));
            if (row >= first && row < last) {  // the band's own rows: differences and histograms
                const std::uint8_t* inside = &mask.inside[at];
                std::int64_t squared = 0, absolute = 0, worst = 0;
                for (std::size_t c = 0; c < plane; ++c) {
                    if (!inside[c]) continue;
                    const T* a = p.pixel(at + c);
                    const T* b = q.pixel(at + c);
                    if (p.channels == q.channels) {
                        for (int k = 0; k < q.channels; ++k) {
                            const std::int64_t d = static_cast<std::int64_t>(a[k]) - b[k], m = d < 0 ? -d : d;
                            squared += d * d, absolute += m, worst = std::max(worst, m);
                        }
                    } else {  // a grey prediction of a colour photo or the reverse: its grey against each channel
                        const double grey = greyP[c] / static_cast<double>(p.channels);
                        for (int k = 0; k < q.channels; ++k) {
                            const double d = grey - b[k];
                            out.squared += d * d, out.absolute += std::abs(d),
                                out.worst = std::max(out.worst, std::abs(d));
                        }
                    }
                    ++out.pixels;
                    ++out.binsP[p.binOf[greyP[c]]];
                    ++out.binsQ[q.binOf[greyQ[c]]];
                }
                out.squared += static_cast<double>(squared), out.absolute += static_cast<double>(absolute);
                out.worst = std::max(out.worst, static_cast<double>(worst));
            }
            const int done = row - kRadius;  // the row whose window is now complete
            if (done < first) continue;
            const std::uint8_t* inside = &mask.inside[static_cast<std::size_t>(done) * plane];
            out.ssim += ssimRow(ring.data(), (done - first + kTaps - kRadius) % kTaps, plane, g, inside, s.data());
        }
    });
    ImageErrors e;
    BandSums all;
    double ssim = 0;
    for (const BandSums& b : sums) {
        all.squared += b.squared, all.absolute += b.absolute, all.worst = std::max(all.worst, b.worst);
        all.pixels += b.pixels, ssim += b.ssim;
        for (int k = 0; k < 64; ++k) all.binsP[k] += b.binsP[k], all.binsQ[k] += b.binsQ[k];
    }
    const auto pixels = static_cast<double>(all.pixels);
    std::vector<double> hp(64, 0.0), hq(64, 0.0);
    if (all.pixels > 0)
        for (int k = 0; k < 64; ++k)
            hp[k] = static_cast<double>(all.binsP[k]) / pixels, hq[k] = static_cast<double>(all.binsQ[k]) / pixels;
    for (int k = 0; k < 64; ++k) e.l1 += std::abs(hp[k] - hq[k]);
    e.emd = earthMoversDistance(hp, hq);
    const double samples = pixels * q.channels, squared = all.squared / (maxCode * maxCode);
    e.maxDifference = all.worst / maxCode;
    e.meanDifference = all.pixels > 0 ? all.absolute / maxCode / samples : 0.0;
    e.psnr = all.pixels == 0 || squared == 0 ? 99.0 : std::min(99.0, 10 * std::log10(samples / squared));
    e.ssim = all.pixels > 0 ? ssim / pixels : 1.0;
    return e;
}

// Codes at another bit depth (8 <-> 16), rounded.
ImageCodes recoded(const ImageCodes& c, int bitDepth) { return toCodes(toImage(c), bitDepth); }

}  // namespace

Image quantised(const Image& image, int bitDepth) {
    Image out = image;
    const double scale = bitDepth == 16 ? 65535.0 : 255.0;
    for (float& v : out.samples)
        v = static_cast<float>(std::round(std::clamp(static_cast<double>(v), 0.0, 1.0) * scale) / scale);
    out.bitDepth = bitDepth;
    return out;
}

ImageErrors compareCodes(const ImageCodes& predicted, const ImageCodes& photo, const Mask& mask) {
    BTFLUT_CHECK(predicted.width == photo.width && predicted.height == photo.height);
    BTFLUT_CHECK(mask.inside.size() == photo.pixelCount());
    ImageCodes converted;
    const ImageCodes& p =
        predicted.bitDepth == photo.bitDepth ? predicted : (converted = recoded(predicted, photo.bitDepth));
    if (photo.bitDepth == 16)
        return compareViews(viewOf(p, p.sixteen()), viewOf(photo, photo.sixteen()), photo.width, photo.height, 65535.0,
                            mask);
    return compareViews(viewOf(p, p.eight()), viewOf(photo, photo.eight()), photo.width, photo.height, 255.0, mask);
}

ImageErrors compareImages(const Image& predicted, const Image& photo, const Mask& mask) {
    return compareCodes(toCodes(predicted, photo.bitDepth), toCodes(photo, photo.bitDepth), mask);
}

Image errorMap(const Image& predicted, const Image& photo, const Mask& mask, float gain) {
    BTFLUT_CHECK(predicted.width == photo.width && predicted.height == photo.height);
    BTFLUT_CHECK(mask.inside.size() == photo.pixelCount() && gain > 0);
    Image map(photo.width, photo.height, 3);
    for (std::size_t p = 0; p < photo.pixelCount(); ++p) {
        float* out = &map.samples[p * 3];
        if (!mask.inside[p]) {
            out[0] = out[1] = out[2] = 0.85f;
            continue;
        }
        float sum = 0;
        for (int c = 0; c < photo.channels; ++c) {
            const int pc = predicted.channels == 1 ? 0 : std::min(c, predicted.channels - 1);
            sum += std::abs(predicted.samples[p * static_cast<std::size_t>(predicted.channels) + pc] -
                            photo.samples[p * static_cast<std::size_t>(photo.channels) + c]);
        }
        // Hot: red rises over the first third, green the second, blue the last.
        const float e = std::clamp(gain * sum / static_cast<float>(photo.channels), 0.f, 1.f);
        out[0] = std::min(1.f, 3 * e);
        out[1] = std::clamp(3 * e - 1, 0.f, 1.f);
        out[2] = std::clamp(3 * e - 2, 0.f, 1.f);
    }
    return map;
}

PairedDifference pairedDifference(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size() || a.empty()) return {};
    double sum = 0, squares = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = a[i] - b[i];
        if (std::isnan(d)) return {};
        sum += d;
        squares += d * d;
    }
    const auto n = static_cast<double>(a.size());
    const double mean = sum / n, variance = std::max(0.0, squares / n - mean * mean);
    return {mean, std::sqrt(variance / std::max(1.0, n - 1))};
}

double targetL1(const std::vector<std::vector<float>>& quantiles, const std::vector<double>& weights,
                const Image& photo, const Mask& mask) {
    BTFLUT_CHECK(quantiles.size() == weights.size() && !quantiles.empty());
    // The photo's side as compareImages bins it: grey codes (the channels' codes summed), 64 bins.
    const LevelCounts levels = countGreyLevels(photo, mask);
    const std::vector<double> measured = binHistogram(levels, 64);
    const std::uint64_t last = levels.counts.size() - 1;
    double total = 0;
    for (double w : weights) total += w;
    if (levels.total() == 0 || !(total > 0)) return std::nan("");
    std::vector<double> target(64, 0.0);
    for (std::size_t r = 0; r < quantiles.size(); ++r) {
        if (quantiles[r].empty()) continue;
        const double share = weights[r] / total / static_cast<double>(quantiles[r].size());
        for (float v : quantiles[r]) {  // at the nearest grey code, in that code's bin (binHistogram's)
            const auto code =
                static_cast<std::uint64_t>(std::llround(std::clamp(double{v}, 0.0, 1.0) * static_cast<double>(last)));
            target[std::min<std::uint64_t>(code * 64 / last, 63)] += share;
        }
    }
    double l1 = 0;
    for (std::size_t k = 0; k < 64; ++k) l1 += std::abs(measured[k] - target[k]);
    return l1;
}

}  // namespace btflut
