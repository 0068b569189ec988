#include "core/metrics.h"

#include <algorithm>
#include <cmath>

#include "core/histogram.h"
#include "core/parallel.h"

namespace btflut {

namespace {

// Mean SSIM (Wang et al. 2004) of two grey images over a mask: Gaussian windows (sigma 1.5,
// radius 5, edges clamped) of x, y, xx, yy and xy. One horizontal pass into five float
// planes, then per output row the vertical sums and the SSIM term at once, rows in parallel
// (each row's sum kept apart and added in order, so the result does not depend on threads).
double meanSsim(const Image& p, const Image& q, const Mask& mask) {
    constexpr int kRadius = 5;
    double weights[2 * kRadius + 1], sum = 0;
    for (int k = -kRadius; k <= kRadius; ++k) sum += weights[k + kRadius] = std::exp(-0.5 * k * k / (1.5 * 1.5));
    float kernel[2 * kRadius + 1];
    for (int k = 0; k < 2 * kRadius + 1; ++k) kernel[k] = static_cast<float>(weights[k] / sum);
    const int w = q.width, h = q.height;
    const std::size_t n = q.pixelCount();
    std::vector<float> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = p.grey(i), y[i] = q.grey(i);
    std::vector<float> planes(5 * n);  // horizontal sums of x, y, xx, yy, xy
    parallelFor(static_cast<std::size_t>(h), 0, [&](std::size_t row) {
        const float* xr = &x[row * w];
        const float* yr = &y[row * w];
        for (int c = 0; c < w; ++c) {
            float s[5] = {0, 0, 0, 0, 0};
            for (int k = -kRadius; k <= kRadius; ++k) {
                const int at = std::clamp(c + k, 0, w - 1);
                const float a = xr[at], b = yr[at], g = kernel[k + kRadius];
                s[0] += g * a, s[1] += g * b, s[2] += g * a * a, s[3] += g * b * b, s[4] += g * a * b;
            }
            for (int m = 0; m < 5; ++m) planes[m * n + row * w + c] = s[m];
        }
    });
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    std::vector<double> rowTotal(static_cast<std::size_t>(h), 0.0);
    parallelFor(static_cast<std::size_t>(h), 0, [&](std::size_t row) {
        std::vector<float> s(5 * static_cast<std::size_t>(w), 0.f);
        for (int k = -kRadius; k <= kRadius; ++k) {
            const std::size_t from = static_cast<std::size_t>(std::clamp(static_cast<int>(row) + k, 0, h - 1)) * w;
            const float g = kernel[k + kRadius];
            for (int m = 0; m < 5; ++m)
                for (int c = 0; c < w; ++c) s[m * w + c] += g * planes[m * n + from + c];
        }
        double total = 0;
        for (int c = 0; c < w; ++c) {
            if (!mask.inside[row * w + c]) continue;
            const double mx = s[c], my = s[w + c];
            const double vx = s[2 * w + c] - mx * mx, vy = s[3 * w + c] - my * my, cxy = s[4 * w + c] - mx * my;
            total += (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
        }
        rowTotal[row] = total;
    });
    double total = 0;
    for (double t : rowTotal) total += t;
    const std::size_t inside = mask.count();
    return inside ? total / static_cast<double>(inside) : 1.0;
}

// True when every sample is a code of `bitDepth` bits already (as decoded from a file). A
// branch-free pass the compiler vectorises.
bool isQuantised(const Image& image, int bitDepth) {
    const float scale = bitDepth == 16 ? 65535.f : 255.f;
    float worst = 0.f;
    for (float v : image.samples) {
        const float code = std::clamp(v, 0.f, 1.f) * scale;
        worst = std::max(worst, std::abs(code - static_cast<float>(static_cast<int>(code + 0.5f))) + std::abs(v - std::clamp(v, 0.f, 1.f)));
    }
    return worst <= 1e-3f;  // NaN samples make `worst` NaN: not quantised
}

}  // namespace

Image quantised(const Image& image, int bitDepth) {
    Image out = image;
    const double scale = bitDepth == 16 ? 65535.0 : 255.0;
    for (float& v : out.samples) v = static_cast<float>(std::round(std::clamp(static_cast<double>(v), 0.0, 1.0) * scale) / scale);
    out.bitDepth = bitDepth;
    return out;
}

ImageErrors compareImages(const Image& predicted, const Image& photo, const Mask& mask) {
    BTFLUT_CHECK(predicted.width == photo.width && predicted.height == photo.height);
    BTFLUT_CHECK(mask.inside.size() == photo.pixelCount());
    // Quantised to the photo's codes; images decoded from files already are (no copies).
    Image pCopy, qCopy;
    const Image& p = isQuantised(predicted, photo.bitDepth) ? predicted : (pCopy = quantised(predicted, photo.bitDepth));
    const Image& q = isQuantised(photo, photo.bitDepth) ? photo : (qCopy = quantised(photo, photo.bitDepth));
    ImageErrors e;
    // Histograms of exact codes: grey of the prediction's own channels.
    const std::vector<double> hp = binHistogram(countGreyLevels(p, mask), 64), hq = binHistogram(countGreyLevels(q, mask), 64);
    for (std::size_t b = 0; b < hp.size(); ++b) e.l1 += std::abs(hp[b] - hq[b]);
    e.emd = earthMoversDistance(hp, hq);

    // Per row in parallel (each row's sums kept apart and added in order: the same result
    // whatever the threads).
    struct Row {
        double squared = 0, absolute = 0, worst = 0;
        std::size_t count = 0;
    };
    std::vector<Row> perRow(static_cast<std::size_t>(q.height));
    const auto w = static_cast<std::size_t>(q.width);
    const bool same = p.channels == q.channels;
    parallelFor(perRow.size(), 0, [&](std::size_t y) {
        Row r;
        for (std::size_t i = y * w; i < (y + 1) * w; ++i) {
            if (!mask.inside[i]) continue;
            const float grey = same ? 0.f : p.grey(i);
            for (int c = 0; c < q.channels; ++c) {
                const float d = (same ? p.samples[i * q.channels + c] : grey) - q.samples[i * q.channels + c];
                r.squared += static_cast<double>(d) * d;
                r.absolute += std::abs(d);
                r.worst = std::max(r.worst, static_cast<double>(std::abs(d)));
            }
            r.count += static_cast<std::size_t>(q.channels);
        }
        perRow[y] = r;
    });
    double squared = 0;
    std::size_t count = 0;
    for (const Row& r : perRow) {
        squared += r.squared;
        e.meanDifference += r.absolute;
        e.maxDifference = std::max(e.maxDifference, r.worst);
        count += r.count;
    }
    if (count > 0) e.meanDifference /= static_cast<double>(count);
    e.psnr = count == 0 || squared == 0 ? 99.0 : std::min(99.0, 10 * std::log10(static_cast<double>(count) / squared));

    e.ssim = meanSsim(p, q, mask);
    return e;
}

}  // namespace btflut
