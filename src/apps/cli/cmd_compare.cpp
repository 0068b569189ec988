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
#include "core/eval/image_compare.h"
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
    CompareFigures f;
    std::vector<std::string> failed;  // the bounds it is outside of (kept when updated)
    bool ok() const { return problem.empty() && (failed.empty() || updated); }
};

std::string psnrText(const CompareFigures& f) {
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
        *a = cropped(*a, c.x, c.y, c.width, c.height);
        *b = cropped(*b, c.x, c.y, c.width, c.height);
        Mask part = fullMask(c.width, c.height);
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x)
                part.inside[static_cast<std::size_t>(y) * c.width + x] =
                    mask.inside[static_cast<std::size_t>(c.y + y) * mask.width + c.x + x];
        mask = std::move(part);
    }
    if (!o.mask.empty() && mask.count() == 0) return Error{o.mask + ": the mask has no pixels to compare"};
    alphaFigures(*a, *b, mask, t.threshold, r.f);
    if (!alphaWithin(r.f, t)) r.failed.push_back("alpha");
    makeComparable(*a, *b);
    differenceFigures(*a, *b, mask, t.threshold, r.f);
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
