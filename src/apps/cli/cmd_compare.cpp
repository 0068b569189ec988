// btflut compare: two images side by side for screenshot tests, with a tolerance and exit status.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli.h"
#include "core/eval/metrics.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"
#include "core/parallel.h"

namespace btflut::cli {

namespace {

struct CompareOptions {
    std::string actual;
    std::string expected;
    std::string mask;
    std::string tolerance = "max=1";
    std::string diff;
    bool json = false;
    bool update = false;
    bool outside = false;  // set by the run: exit status 1
};

// A bound on one figure: psnr and ssim from below, the rest from above; max, mean and p99 in 1/255.
struct Bound {
    std::string name;
    double limit = 0;
};

const char* const kFigures[] = {"psnr", "ssim", "max", "mean", "p99", "l1", "emd"};

Result<std::vector<Bound>> parseTolerance(const std::string& text) {
    std::vector<Bound> bounds;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        const auto equals = item.find('=');
        const std::string name = item.substr(0, equals);
        if (equals == std::string::npos || std::find(std::begin(kFigures), std::end(kFigures), name) == std::end(kFigures))
            return Error{"--tolerance '" + text + "': expected NAME=VALUE,... with NAME one of psnr, ssim, max, mean, p99, l1, emd"};
        const std::string value = item.substr(equals + 1);
        char* end = nullptr;
        const double limit = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !std::isfinite(limit) || limit < 0)
            return Error{"--tolerance '" + text + "': '" + value + "' is not a non-negative number"};
        bounds.push_back({name, limit});
    }
    if (bounds.empty()) return Error{"--tolerance is empty"};
    return bounds;
}

// The errors, and the 99th percentile of the samples' absolute difference over the mask (in
// 1/255): a bound that lets a few samples be far off, as two renderers that round a value
// differently leave them where a LUT is steep, and still catches a wrong image.
struct Figures {
    ImageErrors e;
    double p99 = 0;
};

double percentile99(const Image& a, const Image& b, const Mask& mask) {
    std::vector<float> differences;
    const auto channels = static_cast<std::size_t>(b.channels);
    for (std::size_t i = 0; i < b.pixelCount(); ++i)
        if (mask.inside[i])
            for (std::size_t c = 0; c < channels; ++c) differences.push_back(std::abs(a.samples[i * channels + c] - b.samples[i * channels + c]));
    if (differences.empty()) return 0;
    auto at = differences.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(differences.size() - 1));
    std::nth_element(differences.begin(), at, differences.end());
    return *at * 255.0;
}

double figure(const Figures& f, const std::string& name) {
    const ImageErrors& e = f.e;
    if (name == "p99") return f.p99;
    if (name == "psnr") return e.psnr;
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
// channel difference (8/255 and more: full red; any difference at least a quarter), outside
// the mask dark blue.
Image differenceImage(const Image& a, const Image& b, const Mask& mask) {
    Image out(b.width, b.height, 3);
    for (std::size_t i = 0; i < b.pixelCount(); ++i) {
        float* rgb = &out.samples[i * 3];
        if (!mask.inside[i]) {
            rgb[0] = 0.05f, rgb[1] = 0.05f, rgb[2] = 0.2f;
            continue;
        }
        double worst = 0;
        for (int c = 0; c < b.channels; ++c)
            worst = std::max(worst, std::abs(static_cast<double>(a.samples[i * a.channels + c]) - b.samples[i * b.channels + c]));
        const float base = 0.3f * b.grey(i);
        rgb[0] = rgb[1] = rgb[2] = base;
        if (worst > 0.5 / 65535) {
            rgb[0] = static_cast<float>(std::clamp(worst * 255 / 8, 0.25, 1.0));
            rgb[1] = rgb[2] = 0;
        }
    }
    return out;
}

Status copyFile(const std::string& from, const std::string& to) {
    Result<Bytes> bytes = readFile(from);
    if (!bytes) return Error{bytes.error()};
    return writeFileAtomically(to, *bytes);
}

Status runCompare(CompareOptions& o) {
    Result<std::vector<Bound>> bounds = parseTolerance(o.tolerance);
    if (!bounds) return Error{bounds.error()};
    if (!o.diff.empty())
        if (Status s = requireExtension(o.diff, {"png"}, "--diff"); !s) return s;
    std::error_code ec;
    if (o.update && !std::filesystem::exists(o.expected, ec)) {  // a new golden image
        if (Result<ImageCodes> a = loadImageCodes(o.actual); !a) return Error{a.error()};  // a readable image
        if (Status s = copyFile(o.actual, o.expected); !s) return s;
        std::cout << "created " << o.expected << " from " << o.actual << "\n";
        return success();
    }
    // Both decoded at once, to their codes (decoding is most of the time).
    std::optional<Result<ImageCodes>> images[2];
    parallelFor(2, 0, [&](std::size_t k) { images[k] = loadImageCodes(k == 0 ? o.actual : o.expected); });
    Result<ImageCodes>& a = *images[0];
    Result<ImageCodes>& b = *images[1];
    if (!a) return Error{a.error()};
    if (!b) return Error{b.error()};
    if (a->width != b->width || a->height != b->height)
        return Error{o.actual + " is " + std::to_string(a->width) + "x" + std::to_string(a->height) + ", " + o.expected +
                     " is " + std::to_string(b->width) + "x" + std::to_string(b->height) + ": images of different sizes"};
    if (a->channels != b->channels)
        return Error{o.actual + " has " + std::to_string(a->channels) + " channel(s), " + o.expected + " has " +
                     std::to_string(b->channels) + ": images of different channel counts"};
    Mask mask = fullMask(b->width, b->height);
    if (!o.mask.empty()) {
        Result<Mask> loaded = loadMask(o.mask, b->width, b->height);
        if (!loaded) return Error{loaded.error()};
        mask = std::move(*loaded);
        if (mask.count() == 0) return Error{o.mask + ": the mask has no pixels to compare"};
    }
    Figures f{compareCodes(*a, *b, mask)};
    const ImageErrors& e = f.e;
    const bool wantsP99 = o.json || std::any_of(bounds->begin(), bounds->end(), [](const Bound& bound) { return bound.name == "p99"; });
    if (wantsP99) f.p99 = percentile99(quantised(toImage(*a), b->bitDepth), toImage(*b), mask);
    std::vector<std::string> failed;
    for (const Bound& bound : *bounds)
        if (!within(f, bound)) failed.push_back(bound.name);
    o.outside = !failed.empty();
    if (!o.diff.empty()) {
        const Bytes png = encodePng(differenceImage(quantised(toImage(*a), b->bitDepth), toImage(*b), mask), 8);
        if (Status s = writeFileAtomically(o.diff, png); !s) return s;
    }
    if (o.json) {
        nlohmann::json out{{"a", o.actual}, {"b", o.expected}, {"psnr", e.psnr}, {"ssim", e.ssim},
                           {"max_255", e.maxDifference * 255}, {"mean_255", e.meanDifference * 255}, {"p99_255", f.p99},
                           {"l1", e.l1}, {"emd", e.emd}, {"tolerance", o.tolerance}, {"within", failed.empty()},
                           {"failed", failed}};
        std::cout << jsonText(out);
    } else {
        char line[320];
        std::snprintf(line, sizeof line,
                      "psnr %.2f dB, ssim %.4f, max %.2f/255, mean %.3f/255, histogram l1 %.4f, emd %.5f: %s\n", e.psnr,
                      e.ssim, e.maxDifference * 255, e.meanDifference * 255, e.l1, e.emd,
                      failed.empty() ? ("within " + o.tolerance).c_str() : "OUTSIDE the tolerance");
        std::cout << line;
        if (wantsP99) std::printf("  p99 %.2f/255\n", f.p99);
        for (const std::string& name : failed)
            for (const Bound& bound : *bounds)
                if (bound.name == name)
                    std::cout << "  " << name << " " << figure(f, name) << (name == "psnr" || name == "ssim" ? " < " : " > ")
                              << bound.limit << "\n";
    }
    if (o.outside && o.update) {
        if (Status s = copyFile(o.actual, o.expected); !s) return s;
        std::cout << "updated " << o.expected << " from " << o.actual << "\n";
        o.outside = false;
    }
    return success();
}

}  // namespace

void addCompareCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* app = root.add_subcommand(
        "compare", "Compare two images for screenshot tests: exit 0 within the tolerance, 1 outside it, 2 on bad input");
    app->add_option("A", o->actual, "the image to check (a render)")->required();
    app->add_option("B", o->expected, "the expected image (the golden file)")->required();
    app->add_option("--mask", o->mask, "compare only where the mask is non-zero");
    app->add_option("--tolerance", o->tolerance,
                    "NAME=VALUE,...: psnr (dB) and ssim at least, max, mean and p99 (absolute difference in 1/255; p99 "
                    "the 99th percentile of the samples'), l1 and emd (masked 64-bin grey histograms) at most")
        ->capture_default_str();
    app->add_option("--diff", o->diff, "diff.png: where they differ (red, full at 8/255), over the expected image dimmed");
    app->add_flag("--json", o->json, "print JSON");
    app->add_flag("--update", o->update,
                  "golden-file update: write A over B when B is missing or outside the tolerance (exit 0)");
    commands.push_back({app, [o] { return runCompare(*o); }, 2, [o] { return o->outside ? 1 : 0; }});
}

}  // namespace btflut::cli
