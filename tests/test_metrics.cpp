// The image metrics (core/eval/metrics.h) against a plain reference written from their
// definitions: double precision, a 2D Gaussian window per pixel, histograms of exact codes.
// The fast pass works in bands of 64 rows with a ring of row sums, so the images here are
// taller than one band and not a multiple of it.
#include <doctest/doctest.h>
#include <set>

#include <algorithm>
#include <cmath>

#include "core/eval/charts.h"
#include "core/eval/metrics.h"
#include "core/histogram/histogram.h"
#include "core/histogram/lut.h"
#include "core/image/canvas.h"
#include "core/random.h"

using namespace btflut;

namespace {

Image randomImage(int w, int h, int channels, int bitDepth, std::uint64_t seed) {
    Image image(w, h, channels, bitDepth);
    Random random(seed);
    const double top = bitDepth == 16 ? 65535 : 255;
    // A smooth pattern plus noise, as codes (so SSIM sees structure, not only noise).
    for (int row = 0; row < h; ++row)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                const double v = 0.5 + 0.3 * std::sin(0.21 * x + 0.13 * row + c) + 0.15 * (random.uniform() - 0.5);
                image.at(x, row, c) = static_cast<float>(std::round(std::clamp(v, 0.0, 1.0) * top) / top);
            }
    return image;
}

// A copy with some samples moved by a few codes.
Image disturbed(const Image& image, std::uint64_t seed) {
    Image out = image;
    Random random(seed);
    const double top = image.maxCode();
    for (float& v : out.samples)
        if (random.uniform() < 0.3)
            v = static_cast<float>(std::clamp(std::round(v * top + (random.uniform() - 0.5) * 40), 0.0, top) / top);
    return out;
}

Mask randomMask(int w, int h, std::uint64_t seed) {
    Mask mask = fullMask(w, h);
    Random random(seed);
    for (std::uint8_t& m : mask.inside) m = random.uniform() < 0.8 ? 1 : 0;
    return mask;
}

// Every figure from its definition, with both images already codes of the photo's depth.
ImageErrors reference(const Image& p, const Image& q, const Mask& mask) {
    ImageErrors e;
    const auto hp = binHistogram(countGreyLevels(p, mask), 64), hq = binHistogram(countGreyLevels(q, mask), 64);
    for (std::size_t b = 0; b < hp.size(); ++b) e.l1 += std::abs(hp[b] - hq[b]);
    e.emd = earthMoversDistance(hp, hq);
    const double top = q.maxCode();
    auto value = [&](const Image& image, std::size_t i, int c) {
        return std::round(image.samples[i * image.channels + c] * top) / top;
    };
    auto grey = [&](const Image& image, std::size_t i) {
        double sum = 0;
        for (int c = 0; c < image.channels; ++c) sum += value(image, i, c);
        return sum / image.channels;
    };
    double squared = 0, absolute = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < q.pixelCount(); ++i) {
        if (!mask.inside[i]) continue;
        for (int c = 0; c < q.channels; ++c) {
            const double d = (p.channels == q.channels ? value(p, i, c) : grey(p, i)) - value(q, i, c);
            squared += d * d, absolute += std::abs(d), e.maxDifference = std::max(e.maxDifference, std::abs(d));
            ++count;
        }
    }
    e.meanDifference = absolute / static_cast<double>(count);
    e.psnr = squared == 0 ? 99.0 : std::min(99.0, 10 * std::log10(static_cast<double>(count) / squared));
    // SSIM: an 11 x 11 Gaussian window (sigma 1.5, normalised), edges clamped.
    double weights[11], sum = 0;
    for (int k = -5; k <= 5; ++k) sum += weights[k + 5] = std::exp(-0.5 * k * k / 2.25);
    for (double& wgt : weights) wgt /= sum;
    const int w = q.width, h = q.height;
    double total = 0;
    std::size_t inside = 0;
    for (int row = 0; row < h; ++row)
        for (int x = 0; x < w; ++x) {
            if (!mask.inside[static_cast<std::size_t>(row) * w + x]) continue;
            double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
            for (int j = -5; j <= 5; ++j)
                for (int i = -5; i <= 5; ++i) {
                    const std::size_t at =
                        static_cast<std::size_t>(std::clamp(row + j, 0, h - 1)) * w + std::clamp(x + i, 0, w - 1);
                    const double g = weights[j + 5] * weights[i + 5], a = grey(p, at), b = grey(q, at);
                    mx += g * a, my += g * b, xx += g * a * a, yy += g * b * b, xy += g * a * b;
                }
            const double c1 = 1e-4, c2 = 9e-4, vx = xx - mx * mx, vy = yy - my * my, cxy = xy - mx * my;
            total += (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            ++inside;
        }
    e.ssim = total / static_cast<double>(inside);
    return e;
}

void checkClose(const ImageErrors& got, const ImageErrors& want) {
    CHECK(got.l1 == doctest::Approx(want.l1).epsilon(1e-12));
    CHECK(got.emd == doctest::Approx(want.emd).epsilon(1e-12));
    CHECK(got.psnr == doctest::Approx(want.psnr).epsilon(1e-9));
    CHECK(got.maxDifference == doctest::Approx(want.maxDifference).epsilon(1e-6));
    CHECK(got.meanDifference == doctest::Approx(want.meanDifference).epsilon(1e-6));
    CHECK(got.ssim == doctest::Approx(want.ssim).epsilon(1e-5));  // float sums in the fast pass
}

}  // namespace

TEST_CASE("metrics: every figure equals its definition (8 and 16 bits, grey and colour, masks)") {
    const int w = 53, h = 150;  // three bands, the last one short
    for (int depth : {8, 16})
        for (int channels : {1, 3}) {
            INFO("depth " << depth << ", channels " << channels);
            const Image photo = randomImage(w, h, channels, depth, 7);
            const Image predicted = disturbed(photo, 11);
            const Mask mask = randomMask(w, h, 3);
            checkClose(compareImages(predicted, photo, mask), reference(predicted, photo, mask));
            checkClose(compareImages(predicted, photo, fullMask(w, h)), reference(predicted, photo, fullMask(w, h)));
            // From codes, as `compare` reads files: the same figures.
            checkClose(compareCodes(toCodes(predicted, depth), toCodes(photo, depth), mask),
                       reference(predicted, photo, mask));
        }
}

TEST_CASE("metrics: a grey prediction of a colour photo, depths that differ, samples off the codes") {
    const int w = 40, h = 70;
    const Image photo = randomImage(w, h, 3, 8, 5);
    const Mask mask = randomMask(w, h, 9);
    Image grey(w, h, 1, 8);
    for (std::size_t i = 0; i < photo.pixelCount(); ++i) grey.samples[i] = std::round(photo.grey(i) * 255) / 255;
    checkClose(compareImages(grey, photo, mask), reference(grey, photo, mask));
    // A 16-bit prediction against an 8-bit photo: quantised to the photo's codes first.
    Image fine = disturbed(photo, 4);
    fine.bitDepth = 16;
    for (float& v : fine.samples) v = std::clamp(v + 0.0007f, 0.f, 1.f);  // between 8-bit codes
    checkClose(compareImages(fine, photo, mask), reference(quantised(fine, 8), photo, mask));
    checkClose(compareCodes(toCodes(fine, 16), toCodes(photo, 8), mask), reference(quantised(fine, 8), photo, mask));
    // NaN, below 0 and above 1 in a float prediction: as 0, 0 and 1.
    Image odd = photo;
    odd.samples[0] = std::nanf(""), odd.samples[1] = -0.5f, odd.samples[2] = 1.5f;
    Image clamped = photo;
    clamped.samples[0] = 0.f, clamped.samples[1] = 0.f, clamped.samples[2] = 1.f;
    checkClose(compareImages(odd, photo, fullMask(w, h)), reference(clamped, photo, fullMask(w, h)));
}

TEST_CASE("metrics: identical images") {
    const Image image = randomImage(31, 66, 3, 8, 2);
    const ImageErrors e = compareImages(image, image, fullMask(31, 66));
    CHECK(e.psnr == 99.0);
    CHECK(e.ssim == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(e.maxDifference == 0.0);
    CHECK(e.meanDifference == 0.0);
    CHECK(e.l1 == 0.0);
    CHECK(e.emd == 0.0);
}

TEST_CASE("charts: the Pareto front, and panels drawn with missing figures") {
    // cost, value: (1, 10) (2, 9) (2, 12) (3, 12) (4, 15) (NaN, 99)
    const std::vector<double> cost{1, 2, 2, 3, 4, std::nan("")}, value{10, 9, 12, 12, 15, 99};
    CHECK(paretoFront(cost, value, Better::Higher) == std::vector<std::size_t>{0, 2, 4});
    CHECK(paretoFront(cost, value, Better::Lower) == std::vector<std::size_t>{0, 1});
    CHECK(paretoFront({}, {}, Better::Higher).empty());
    ChartPanel points{.title = "t", .xLabel = "x", .yLabel = "y", .logX = true, .pareto = Better::Higher};
    for (std::size_t i = 0; i < cost.size(); ++i)
        points.series.push_back({"p" + std::to_string(i), {cost[i]}, {value[i]}});
    ChartPanel empty{.title = "nothing", .xLabel = "x", .yLabel = "y"};
    empty.series.push_back({"nan", {std::nan("")}, {1.0}});
    ChartPanel lines{.title = "lines", .xLabel = "theta", .yLabel = "dB", .lines = true};
    lines.series.push_back({"a", {5, 15, 25}, {30, 28, 20}});
    const Image chart = drawCharts({points, empty, lines}, 2);
    CHECK(chart.width > 2 * 400);
    CHECK(chart.height > 2 * 300);
    std::size_t coloured = 0;  // the points and lines are drawn in colour, the axes and text grey
    for (int y = 0; y < chart.height; ++y)
        for (int x = 0; x < chart.width; ++x) coloured += std::abs(chart.at(x, y, 0) - chart.at(x, y, 2)) > 0.2f;
    CHECK(coloured > 100);
}

TEST_CASE("charts: a series with no figure is named under the title, not dropped unseen") {
    ChartPanel panel{.title = "PSNR against frame time", .xLabel = "ms", .yLabel = "dB"};
    panel.series.push_back({"lut auto", {2.0}, {30.0}});
    ChartPanel withMissing = panel;
    withMissing.series.push_back({"neuralrti", {std::nan("")}, {25.0}});
    auto inkUnderTitle = [](const Image& chart) {  // the rows between the title and the plot area
        std::size_t n = 0;
        for (int y = Canvas::kTextHeight + 4; y < 2 * Canvas::kTextHeight + 4; ++y)
            for (int x = 0; x < chart.width; ++x) n += chart.at(x, y, 0) < 0.9f;
        return n;
    };
    CHECK(inkUnderTitle(drawCharts({withMissing}, 1)) > inkUnderTitle(drawCharts({panel}, 1)) + 20);
}

TEST_CASE("charts: distinct tick numbers, and labels of coincident points apart") {
    // L1 figures 0.1452 .. 0.1462 were all labelled 0.146 at three digits.
    const std::vector<std::string> close = axisTickLabels({0.1452, 0.1462}, false);
    REQUIRE(close.size() >= 3);
    CHECK(std::set<std::string>(close.begin(), close.end()).size() == close.size());
    // Bytes 3..9 on a log axis had one tick (5); every digit where 1, 2, 5 give fewer than three.
    CHECK(axisTickLabels({3, 7, 9}, true) == std::vector<std::string>{"3", "4", "5", "6", "7", "8", "9"});
    CHECK(axisTickLabels({1, 1000}, true).front() == "1");
    // Three labels on one point: each label's pixels are all drawn (none covered by another's).
    auto colourCount = [](const Image& chart, std::size_t series) {
        const Rgb c = paletteColour(series);
        std::size_t n = 0;
        for (int y = 0; y < chart.height; ++y)
            for (int x = 0; x < chart.width; ++x)
                n += std::abs(chart.at(x, y, 0) - c.r) < 1e-3f && std::abs(chart.at(x, y, 1) - c.g) < 1e-3f &&
                     std::abs(chart.at(x, y, 2) - c.b) < 1e-3f;
        return n;
    };
    ChartPanel crowded{.title = "t", .xLabel = "x", .yLabel = "y"};
    for (const char* name : {"lut K1 R1 grey", "brdf", "nearest"}) crowded.series.push_back({name, {3.0}, {0.2}});
    crowded.series.push_back({"far", {9.0}, {0.5}});
    const Image together = drawCharts({crowded}, 1);
    for (std::size_t s = 0; s < 3; ++s) {
        ChartPanel alone = crowded;
        for (std::size_t other = 0; other < 3; ++other)  // the others' labels and points off the chart's area
            if (other != s) alone.series[other].y = {std::nan("")};
        INFO(crowded.series[s].label);
        // The dots coincide (7x7, the last drawn on top); every text pixel stays.
        CHECK(colourCount(together, s) + 49 >= colourCount(drawCharts({alone}, 1), s));
    }
}

TEST_CASE("error map: black where a prediction is exact, white at 1/gain, grey outside the mask") {
    Image photo(3, 1, 3), predicted(3, 1, 1);
    std::fill(photo.samples.begin(), photo.samples.end(), 0.5f);
    predicted.samples = {0.5f, 0.75f, 0.9f};  // exact; 0.25 off in every channel; outside the mask
    const Mask mask{3, 1, {1, 1, 0}};
    const Image map = errorMap(predicted, photo, mask, 4);
    REQUIRE(map.channels == 3);
    for (int c = 0; c < 3; ++c) {
        CHECK(map.at(0, 0, c) == 0.f);
        CHECK(map.at(1, 0, c) == doctest::Approx(1.f));
        CHECK(map.at(2, 0, c) == doctest::Approx(0.85f));
    }
    // Half the scale: red full, green half, no blue.
    predicted.samples[1] = 0.5f + 0.125f;
    const Image half = errorMap(predicted, photo, mask, 4);
    CHECK(half.at(1, 0, 0) == doctest::Approx(1.f));
    CHECK(half.at(1, 0, 1) == doctest::Approx(0.5f));
    CHECK(half.at(1, 0, 2) == 0.f);
}

TEST_CASE("a target's L1: its own distribution scores near 0, a disjoint one 2, regions weighed by their texels") {
    Image photo(32, 32, 1);
    LevelCounts counts;
    counts.counts.assign(256, 0);
    for (std::size_t i = 0; i < photo.pixelCount(); ++i) {
        const int code = 40 + static_cast<int>(i % 97);
        photo.samples[i] = static_cast<float>(code) / 255.f;
        ++counts.counts[static_cast<std::size_t>(code)];
    }
    const Mask all{32, 32, std::vector<std::uint8_t>(photo.pixelCount(), 1)};
    const std::vector<float> own = quantileFunction(counts, 1024);
    CHECK(targetL1({own}, {1.0}, photo, all) < 0.02);
    const std::vector<float> bright(1024, 0.95f);
    CHECK(targetL1({bright}, {1.0}, photo, all) == doctest::Approx(2.0));
    // Two regions: the photo's own distribution with 3/4 of the weight, a disjoint one with 1/4.
    CHECK(targetL1({own, bright}, {3.0, 1.0}, photo, all) == doctest::Approx(0.5).epsilon(0.05));
}
