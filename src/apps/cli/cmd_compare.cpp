// btflut compare: two images (or two folders of them) for screenshot tests, with a tolerance
// and an exit status; a JUnit report for CI dashboards.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "cli/command.h"
#include "core/check.h"
#include "core/data/dataset.h"
#include "core/eval/metrics.h"
#include "core/image/canvas.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"
#include "core/parallel.h"

namespace btflut::cli {

namespace {

namespace fs = std::filesystem;

struct CompareOptions {
    std::string actual;
    std::string expected;
    std::string mask;
    std::string tolerance = "max=1";
    std::string diff;
    std::string sideBySide;
    std::string junit;
    std::string crop;     // X,Y,W,H: compare only that rectangle of both
    double diffFull = 0;  // the difference drawn full red, 1/255; 0: the tolerance's max, else 8
    bool json = false;
    bool quiet = false;
    bool update = false;
    bool outside = false;  // set by the run: exit status 1
};

// A bound on one figure: psnr and ssim from below, the rest from above; max, mean and p99 in
// 1/255, pixels in per cent. `threshold` is no bound: the difference (1/255) beyond which a
// pixel counts in `pixels`.
struct Bound {
    std::string name;
    double limit = 0;
};

struct Tolerance {
    std::vector<Bound> bounds;
    double threshold = 0;
};

const char* const kFigures[] = {"psnr", "ssim", "max", "mean", "p99", "pixels", "l1", "emd", "threshold"};

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
}

Result<Tolerance> parseTolerance(const std::string& text) {
    Tolerance t;
    std::set<std::string> seen;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        item = trimmed(item);
        const auto equals = item.find('=');
        const std::string name = trimmed(item.substr(0, equals));
        if (equals == std::string::npos ||
            std::find(std::begin(kFigures), std::end(kFigures), name) == std::end(kFigures))
            return Error{
                "--tolerance '" + text +
                "': expected NAME=VALUE,... with NAME one of psnr, ssim, max, mean, p99, pixels, l1, emd, threshold"};
        if (!seen.insert(name).second) return Error{"--tolerance '" + text + "': " + name + " is given twice"};
        std::string value = trimmed(item.substr(equals + 1));
        if (name == "pixels" && !value.empty() && value.back() == '%') value.pop_back();
        char* end = nullptr;
        const double limit = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !std::isfinite(limit) || limit < 0)
            return Error{"--tolerance '" + text + "': '" + value + "' is not a non-negative number"};
        if (name == "ssim" && limit > 1)
            return Error{"--tolerance '" + text + "': ssim is at most 1 (identical images), not " + value};
        if (name == "threshold")
            t.threshold = limit;
        else
            t.bounds.push_back({name, limit});
    }
    if (t.bounds.empty())
        return Error{"--tolerance '" + text + "': no bound (psnr, ssim, max, mean, p99, pixels, l1, emd)"};
    return t;
}

// The errors; the 99th percentile of the samples' absolute difference over the mask (1/255),
// a bound that lets a few samples be far off, as two renderers that round a value differently
// leave them where a LUT is steep; and the share of pixels (per cent) whose largest channel
// difference exceeds the threshold, as pixelmatch and ImageMagick's `compare -metric AE -fuzz`
// count them.
struct Figures {
    ImageErrors e;
    double p99 = 0;
    double pixels = 0;
    // The alpha channel's largest difference (1/255; opaque where a file keeps no alpha) and
    // the share of pixels (per cent) where it exceeds the threshold: a pixel made transparent
    // is another image, whatever its colour.
    bool alpha = false;  // either image keeps one
    double alphaMax = 0, alphaPixels = 0;
    bool identical() const { return e.maxDifference == 0 && alphaMax == 0; }
};

// p99 and pixels from the codes of two images of one bit depth, in bands of rows in parallel
// (a histogram of the differences: no float image, no sort; `compare` stays within its time).
void countPixels(const ImageCodes& a, const ImageCodes& b, const Mask& mask, double threshold, Figures& f) {
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

double figure(const Figures& f, const std::string& name) {
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

bool within(const Figures& f, const Bound& b) {
    const double v = figure(f, b.name);
    return b.name == "psnr" || b.name == "ssim" ? v >= b.limit : v <= b.limit;
}

// Where the images differ: the expected image dimmed, each differing pixel red by its largest
// channel difference (`full` /255 and more: full red; any difference at least a quarter),
// outside the mask dark blue.
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

// Expected | actual | difference, side by side, RGB, under a strip that names each pane.
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

Status copyFile(const std::string& from, const std::string& to) {
    Result<Bytes> bytes = readFile(from);
    if (!bytes) return Error{bytes.error()};
    return writeFileAtomically(to, *bytes);
}

// One comparison's outcome, for the printed line, the JSON and the JUnit report.
struct Outcome {
    std::string name;      // the file name (folders) or the actual image's path
    std::string problem;   // set when the images could not be compared (missing, unreadable, another size)
    std::string note;      // "created ...", "updated ..."
    bool created = false;  // a new golden image: nothing compared
    bool updated = false;  // outside the tolerance, and the golden image replaced (--update)
    Figures f;
    std::vector<std::string> failed;  // the bounds it is outside of (kept when updated)
    bool ok() const { return problem.empty() && (failed.empty() || updated); }
};

std::string psnrText(const Figures& f) {
    char text[32];
    if (f.identical()) return "inf (identical)";
    if (f.e.maxDifference == 0) return "inf (colour identical)";
    std::snprintf(text, sizeof text, "%.2f dB", f.e.psnr);
    return text;
}

std::string line(const Outcome& r, const Tolerance& t, const std::string& tolerance) {
    if (!r.problem.empty()) return r.problem;
    if (r.created) return r.note;
    const ImageErrors& e = r.f.e;
    char text[400];
    std::snprintf(
        text, sizeof text,
        "psnr %s, ssim %.4f, max %.2f/255, mean %.3f/255, p99 %.2f/255, pixels %.3f%% over %g/255, histogram l1 "
        "%.4f, emd %.5f: %s",
        psnrText(r.f).c_str(), e.ssim, e.maxDifference * 255, e.meanDifference * 255, r.f.p99, r.f.pixels, t.threshold,
        e.l1, e.emd, r.failed.empty() ? ("within " + tolerance).c_str() : "OUTSIDE the tolerance");
    std::string out = text;
    if (r.f.alpha) {
        std::snprintf(text, sizeof text, "\n  alpha: max %.2f/255, pixels %.3f%% over %g/255", r.f.alphaMax,
                      r.f.alphaPixels, t.threshold);
        out += text;
    }
    for (const std::string& name : r.failed)
        for (const Bound& bound : t.bounds)
            if (bound.name == name) {
                std::ostringstream s;
                s << "\n  " << name << " " << figure(r.f, name) << (name == "psnr" || name == "ssim" ? " < " : " > ")
                  << bound.limit;
                out += s.str();
            }
    if (!r.note.empty()) out += "\n" + r.note;
    return out;
}

nlohmann::json outcomeJson(const Outcome& r, const CompareOptions& o, const std::string& a, const std::string& b) {
    nlohmann::json out{{"a", a},
                       {"b", b},
                       {"tolerance", o.tolerance},
                       {"within", r.problem.empty() && r.failed.empty()},
                       {"failed", r.failed},
                       {"updated", r.updated || r.created}};
    if (!r.problem.empty() || r.created) {
        out[r.created ? "created" : "problem"] = r.created ? r.note : r.problem;
        return out;
    }
    const ImageErrors& e = r.f.e;
    out.update({{"psnr", r.f.identical() ? nlohmann::json(nullptr) : nlohmann::json(e.psnr)},
                {"identical", r.f.identical()},
                {"alpha_max_255", r.f.alpha ? nlohmann::json(r.f.alphaMax) : nlohmann::json(nullptr)},
                {"alpha_pixels_percent", r.f.alpha ? nlohmann::json(r.f.alphaPixels) : nlohmann::json(nullptr)},
                {"ssim", e.ssim},
                {"max_255", e.maxDifference * 255},
                {"mean_255", e.meanDifference * 255},
                {"p99_255", r.f.p99},
                {"pixels_percent", r.f.pixels},
                {"l1", e.l1},
                {"emd", e.emd}});
    return out;
}

// A rectangle of an image, as `--crop X,Y,W,H` asks (x right, y down from the top-left pixel).
struct Crop {
    int x = 0, y = 0, width = 0, height = 0;
};

Result<std::optional<Crop>> parseCrop(const std::string& text) {
    if (text.empty()) return std::optional<Crop>{};
    int v[4];
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4 || v[0] < 0 || v[1] < 0 ||
        v[2] <= 0 || v[3] <= 0)
        return Error{"--crop '" + text + "': expected X,Y,W,H (pixels; X, Y from the top left, W, H at least 1)"};
    return std::optional<Crop>{Crop{v[0], v[1], v[2], v[3]}};
}

// The part of `image` inside `crop` (the caller checks that it fits).
ImageCodes cropped(const ImageCodes& image, const Crop& crop) {
    ImageCodes out;
    out.width = crop.width;
    out.height = crop.height;
    out.channels = image.channels;
    out.bitDepth = image.bitDepth;
    out.stride = image.stride;
    const std::size_t bytes = static_cast<std::size_t>(image.stride) * (image.bitDepth / 8), row = bytes * crop.width;
    out.bytes = std::make_unique<std::uint8_t[]>(row * static_cast<std::size_t>(crop.height));
    for (int y = 0; y < crop.height; ++y)
        std::memcpy(&out.bytes[row * static_cast<std::size_t>(y)],
                    &image.bytes[(static_cast<std::size_t>(crop.y + y) * image.width + crop.x) * bytes], row);
    return out;
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

// The alpha figures, and "alpha" among the failed bounds where it differs by more than the
// tolerance's max (the threshold when it sets none).
void compareAlpha(const ImageCodes& a, const ImageCodes& b, const Mask& mask, const Tolerance& t, Outcome& r) {
    r.f.alpha = a.stride > a.channels || b.stride > b.channels;
    if (!r.f.alpha) return;
    const std::vector<float> alphaA = alphaOf(a), alphaB = alphaOf(b);
    std::size_t over = 0;
    for (std::size_t i = 0; i < alphaA.size(); ++i) {
        if (!mask.inside[i]) continue;
        const double d = std::abs(static_cast<double>(alphaA[i]) - alphaB[i]) * 255;
        r.f.alphaMax = std::max(r.f.alphaMax, d);
        over += d > t.threshold;
    }
    r.f.alphaPixels = 100.0 * static_cast<double>(over) / static_cast<double>(std::max<std::size_t>(1, mask.count()));
    double limit = t.threshold;
    for (const Bound& bound : t.bounds)
        if (bound.name == "max") limit = bound.limit;
    if (r.f.alphaMax > limit + 1e-9) r.failed.push_back("alpha");
}

// Compares one pair; a problem that stops the pair (unreadable, another size) is an error for a
// pair and a failed row in folders. Writes the diff and side-by-side images it is asked for.
Result<Outcome> compareImages(const CompareOptions& o, const Tolerance& t, const std::string& actual,
                              const std::string& expected, const std::string& diff, const std::string& side) {
    Outcome r;
    r.name = actual;
    std::error_code ec;
    if (o.update && !fs::exists(expected, ec)) {                                         // a new golden image
        if (Result<ImageCodes> a = loadImageCodes(actual); !a) return Error{a.error()};  // a readable image
        if (Status s = copyFile(actual, expected); !s) return Error{s.error()};
        r.note = "created " + expected + " from " + actual;
        r.created = true;
        return r;
    }
    // Both decoded at once, to their codes (decoding is most of the time).
    std::optional<Result<ImageCodes>> images[2];
    parallelFor(2, 0, [&](std::size_t k) { images[k] = loadImageCodes(k == 0 ? actual : expected); });
    Result<ImageCodes>& a = *images[0];
    Result<ImageCodes>& b = *images[1];
    if (!a) return Error{a.error()};
    if (!b) return Error{b.error()};
    if (a->width != b->width || a->height != b->height)
        return Error{actual + " is " + std::to_string(a->width) + "x" + std::to_string(a->height) + ", " + expected +
                     " is " + std::to_string(b->width) + "x" + std::to_string(b->height) +
                     ": images of different sizes"};
    Mask mask = fullMask(b->width, b->height);
    if (!o.mask.empty()) {
        Result<Mask> loaded = loadMask(o.mask, b->width, b->height);
        if (!loaded) return Error{loaded.error()};
        mask = std::move(*loaded);
    }
    if (Result<std::optional<Crop>> crop = parseCrop(o.crop); !crop) {
        return Error{crop.error()};
    } else if (*crop) {
        const Crop c = **crop;
        if (c.x + c.width > b->width || c.y + c.height > b->height)
            return Error{"--crop " + o.crop + ": outside " + expected + " (" + std::to_string(b->width) + "x" +
                         std::to_string(b->height) + ")"};
        *a = cropped(*a, c);
        *b = cropped(*b, c);
        Mask part = fullMask(c.width, c.height);
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x)
                part.inside[static_cast<std::size_t>(y) * c.width + x] =
                    mask.inside[static_cast<std::size_t>(c.y + y) * mask.width + c.x + x];
        mask = std::move(part);
    }
    if (!o.mask.empty() && mask.count() == 0) return Error{o.mask + ": the mask has no pixels to compare"};
    compareAlpha(*a, *b, mask, t, r);
    // Grey against RGB: the grey in all three channels, compared as RGB.
    if (a->channels == 1 && b->channels == 3) *a = asRgb(*a);
    if (a->channels == 3 && b->channels == 1) *b = asRgb(*b);
    r.f.e = compareCodes(*a, *b, mask);
    if (a->bitDepth == b->bitDepth)
        countPixels(*a, *b, mask, t.threshold, r.f);
    else
        countPixels(toCodes(toImage(*a), b->bitDepth), *b, mask, t.threshold, r.f);  // as compareCodes recodes it
    for (const Bound& bound : t.bounds)
        if (!within(r.f, bound)) r.failed.push_back(bound.name);
    if (!diff.empty() || !side.empty()) {
        const Image actualImage = quantised(toImage(*a), b->bitDepth), expectedImage = toImage(*b);
        double full = o.diffFull;
        for (const Bound& bound : t.bounds)
            if (full == 0 && bound.name == "max" && bound.limit > 0) full = bound.limit;
        const Image difference = differenceImage(actualImage, expectedImage, mask, full > 0 ? full : 8);
        if (!diff.empty())
            if (Status s = writeFileAtomically(diff, encodePng(difference, 8)); !s) return Error{s.error()};
        if (!side.empty())
            if (Status s = writeFileAtomically(side, encodePng(sideBySide(actualImage, expectedImage, difference), 8));
                !s)
                return Error{s.error()};
    }
    if (!r.failed.empty() && o.update) {
        if (Status s = copyFile(actual, expected); !s) return Error{s.error()};
        r.note = "updated " + expected + " from " + actual;
        r.updated = true;
    }
    return r;
}

// <testsuite> of one <testcase> per image: a <failure> for each outside the tolerance, an
// <error> for each that could not be compared (missing, unreadable, corrupt, another size).
std::string junitReport(const std::vector<Outcome>& rows, const Tolerance& t, const std::string& tolerance) {
    auto escaped = [](const std::string& s) {
        std::string out;
        for (char c : s) {
            if (c == '&')
                out += "&amp;";
            else if (c == '<')
                out += "&lt;";
            else if (c == '>')
                out += "&gt;";
            else if (c == '"')
                out += "&quot;";
            else
                out += c;
        }
        return out;
    };
    std::size_t failures = 0, errors = 0;
    for (const Outcome& r : rows) {
        errors += !r.problem.empty();
        failures += r.problem.empty() && !r.ok();
    }
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuite name=\"btflut compare\" tests=\"" << rows.size()
      << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n";
    for (const Outcome& r : rows) {
        x << "  <testcase classname=\"btflut.compare\" name=\"" << escaped(r.name) << "\"";
        if (r.ok()) {
            x << "/>\n";
            continue;
        }
        const char* kind = r.problem.empty() ? "failure" : "error";
        x << ">\n    <" << kind << " message=\"" << escaped(r.problem.empty() ? "outside " + tolerance : r.problem)
          << "\">" << escaped(line(r, t, tolerance)) << "</" << kind << ">\n  </testcase>\n";
    }
    x << "</testsuite>\n";
    return x.str();
}

// The image files of a folder and its subfolders, by their paths relative to it (with '/'),
// as golden-image suites lay them out.
Result<std::set<std::string>> imageFiles(const std::string& folder) {
    std::set<std::string> names;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file(ec) && isImageExtension(fileExtension(it->path().string())))
            names.insert(it->path().lexically_relative(folder).generic_string());
    if (ec) return Error{folder + ": cannot list the folder (" + ec.message() + ")"};
    return names;
}

// Where a folder comparison writes an image's diff or side-by-side picture: the image's
// relative path in `folder`, its extension replaced by `suffix` (sub/x.png: sub/x.diff.png).
std::string besideIn(const std::string& folder, const std::string& name, const std::string& suffix) {
    if (folder.empty()) return "";
    const fs::path relative(name);
    return (fs::path(folder) / relative.parent_path() / (relative.stem().string() + suffix)).string();
}

Status runCompare(CompareOptions& o) {
    Result<Tolerance> t = parseTolerance(o.tolerance);
    if (!t) return Error{t.error()};
    std::error_code ec;
    const bool folders = fs::is_directory(o.actual, ec) && fs::is_directory(o.expected, ec);
    if (!folders) {
        for (const auto& [path, option] : {std::pair{o.diff, "--diff"}, std::pair{o.sideBySide, "--side-by-side"}})
            if (!path.empty())
                if (Status s = requireExtension(path, {"png"}, option); !s) return s;
    }
    std::vector<Outcome> rows;
    std::vector<nlohmann::json> json;
    // -q prints what is outside the tolerance, updated golden images included.
    auto shown = [&](const Outcome& r) { return !o.quiet || !r.ok() || r.updated; };
    if (!folders) {
        Result<Outcome> r = compareImages(o, *t, o.actual, o.expected, o.diff, o.sideBySide);
        if (!r) return Error{r.error()};
        if (r->created) {
            if (!o.quiet) std::cout << r->note << "\n";
            return success();
        }
        rows.push_back(*r);
        json.push_back(outcomeJson(*r, o, o.actual, o.expected));
        if (o.json)
            std::cout << jsonText(json.front());
        else if (shown(*r))
            std::cout << line(*r, *t, o.tolerance) << "\n";
    } else {
        // Folders: every image of either, by file name; one line each, every failure listed.
        Result<std::set<std::string>> actual = imageFiles(o.actual), expected = imageFiles(o.expected);
        if (!actual) return Error{actual.error()};
        if (!expected) return Error{expected.error()};
        std::set<std::string> names = *actual;
        names.insert(expected->begin(), expected->end());
        if (names.empty()) return Error{o.actual + ", " + o.expected + ": no images in either folder"};
        for (const std::string& name : names) {
            const std::string a = (fs::path(o.actual) / name).string(), b = (fs::path(o.expected) / name).string();
            Outcome r;
            r.name = name;
            if (!actual->count(name)) {
                r.problem = "no " + name + " in " + o.actual + " (expected " + b + ")";
            } else if (!expected->count(name) && !o.update) {
                r.problem = "no golden image " + b + " (compare --update creates it)";
            } else {
                Result<Outcome> compared = compareImages(o, *t, a, b, besideIn(o.diff, name, ".diff.png"),
                                                         besideIn(o.sideBySide, name, ".side.png"));
                if (compared) {
                    r = std::move(*compared);
                    r.name = name;
                } else {
                    r.problem = compared.error();
                }
            }
            if (!o.json && shown(r)) std::cout << name << ": " << line(r, *t, o.tolerance) << "\n";
            json.push_back(outcomeJson(r, o, a, b));
            rows.push_back(std::move(r));
        }
        std::size_t failed = 0, updated = 0;
        for (const Outcome& r : rows) {
            failed += !r.ok();
            updated += r.updated || r.created;
        }
        if (o.json) {
            std::cout << jsonText(
                nlohmann::json{{"images", json}, {"failed", failed}, {"compared", rows.size()}, {"updated", updated}});
        } else if (!o.quiet || failed > 0 || updated > 0) {
            std::cout << "compared " << rows.size() << " image(s): " << failed << " failed";
            if (o.update) std::cout << ", " << updated << " updated";
            std::cout << "\n";
        }
    }
    if (!o.junit.empty()) {
        const std::string report = junitReport(rows, *t, o.tolerance);
        if (Status s = writeFileAtomically(o.junit, report.data(), report.size()); !s) return s;
    }
    o.outside = std::any_of(rows.begin(), rows.end(), [](const Outcome& r) { return !r.ok(); });
    return success();
}

}  // namespace

void addCompareCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* app = root.add_subcommand("compare",
                                        "Compare two images, or two folders of images by path (subfolders included), "
                                        "for screenshot tests: exit 0 within the "
                                        "tolerance, 1 outside it (any image, for folders), 2 on bad input");
    app->add_option("A", o->actual, "the image to check (a render), or a folder of them")->required();
    app->add_option("B", o->expected, "the expected image (the golden file), or a folder of them")->required();
    app->add_option("--mask", o->mask, "compare only where the mask is non-zero");
    app->add_option(
           "--tolerance", o->tolerance,
           "NAME=VALUE,...: psnr (dB) and ssim at least; max, mean and p99 (absolute difference in 1/255; p99 "
           "the 99th percentile of the samples'), pixels (per cent of the pixels whose largest channel "
           "difference exceeds threshold=T/255, default 0), l1 and emd (masked 64-bin grey histograms) at most")
        ->capture_default_str();
    app->add_option("--diff", o->diff,
                    "diff.png (folders: a folder of NAME.diff.png, laid out as the images): where they differ, red in "
                    "full at the tolerance's max "
                    "(or --diff-full; else 8/255), over the expected image dimmed");
    app->add_option("--diff-full", o->diffFull, "the difference (1/255) drawn full red in --diff")
        ->check(CLI::PositiveNumber);
    app->add_option("--side-by-side", o->sideBySide,
                    "side.png (folders: a folder of NAME.side.png): expected | actual | diff in one image");
    app->add_option("--crop", o->crop,
                    "X,Y,W,H: compare only that rectangle (pixels from the top left), e.g. a render without the "
                    "viewer's panel");
    app->add_option("--junit", o->junit, "report.xml: a JUnit report, one test case per image, for CI dashboards");
    app->add_flag("--json", o->json, "print JSON");
    app->add_flag("--update", o->update,
                  "golden-file update: write A over B when B is missing or outside the tolerance (exit 0)");
    addQuietFlag(*app, o->quiet, "print only what is outside the tolerance (nothing when all is within)");
    commands.push_back({app, [o] { return runCompare(*o); }, 2, [o] { return o->outside ? 1 : 0; }});
}

}  // namespace btflut::cli
