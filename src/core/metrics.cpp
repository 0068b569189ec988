#include "core/metrics.h"

#include <algorithm>
#include <cmath>

#include "core/histogram.h"

namespace btflut {

namespace {

std::vector<double> greyOf(const Image& image) {
    std::vector<double> g(image.pixelCount());
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = image.grey(i);
    return g;
}

// Separable Gaussian blur (sigma 1.5, radius 5), edges clamped.
std::vector<double> blur(const std::vector<double>& v, int width, int height) {
    constexpr int kRadius = 5;
    double kernel[2 * kRadius + 1], sum = 0;
    for (int k = -kRadius; k <= kRadius; ++k) sum += kernel[k + kRadius] = std::exp(-0.5 * k * k / (1.5 * 1.5));
    for (double& k : kernel) k /= sum;
    std::vector<double> rows(v.size()), out(v.size());
    auto at = [](int i, int n) { return std::clamp(i, 0, n - 1); };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double s = 0;
            for (int k = -kRadius; k <= kRadius; ++k) s += kernel[k + kRadius] * v[static_cast<std::size_t>(y) * width + at(x + k, width)];
            rows[static_cast<std::size_t>(y) * width + x] = s;
        }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double s = 0;
            for (int k = -kRadius; k <= kRadius; ++k) s += kernel[k + kRadius] * rows[static_cast<std::size_t>(at(y + k, height)) * width + x];
            out[static_cast<std::size_t>(y) * width + x] = s;
        }
    return out;
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
    const Image p = quantised(predicted, photo.bitDepth), q = quantised(photo, photo.bitDepth);
    ImageErrors e;
    // Histograms of exact codes: grey of the prediction's own channels.
    const std::vector<double> hp = binHistogram(countGreyLevels(p, mask), 64), hq = binHistogram(countGreyLevels(q, mask), 64);
    for (std::size_t b = 0; b < hp.size(); ++b) e.l1 += std::abs(hp[b] - hq[b]);
    e.emd = earthMoversDistance(hp, hq);

    double squared = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < q.pixelCount(); ++i) {
        if (!mask.inside[i]) continue;
        for (int c = 0; c < q.channels; ++c) {
            const float predictedValue = p.channels == q.channels ? p.samples[i * p.channels + c] : p.grey(i);
            const double d = static_cast<double>(predictedValue) - q.samples[i * q.channels + c];
            squared += d * d;
            ++count;
        }
    }
    e.psnr = count == 0 || squared == 0 ? 99.0 : std::min(99.0, 10 * std::log10(static_cast<double>(count) / squared));

    // SSIM (Wang et al. 2004) of the grey images, averaged over the mask.
    const int w = q.width, h = q.height;
    const std::vector<double> x = greyOf(p), y = greyOf(q);
    std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
    const std::vector<double> mx = blur(x, w, h), my = blur(y, w, h), sxx = blur(xx, w, h), syy = blur(yy, w, h),
                              sxy = blur(xy, w, h);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double total = 0;
    std::size_t inside = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (!mask.inside[i]) continue;
        const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cxy = sxy[i] - mx[i] * my[i];
        total += (2 * mx[i] * my[i] + c1) * (2 * cxy + c2) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
        ++inside;
    }
    e.ssim = inside ? total / static_cast<double>(inside) : 1.0;
    return e;
}

}  // namespace btflut
