// btflut eval: the report (a table, JSON, per-image rows and a contact sheet).
#include <cmath>
#include <cstdio>
#include <map>

#include "cli/cli.h"
#include "cli/eval/eval.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"

namespace btflut::cli::eval {

namespace fs = std::filesystem;

Report report(const std::vector<Variant>& variants, const Dataset& dataset, const EvalOptions& o,
              const std::vector<Fold>& folds, std::size_t maskPixels, const std::string& context) {
    std::size_t tests = 0;
    for (const Fold& f : folds) tests += f.test.size();
    nlohmann::json json{{"dataset", dataset.source}, {"images", dataset.images.size()}, {"holdout", o.holdout},
                        {"folds", folds.size()}, {"held_out", tests}, {"mask_pixels", maskPixels}, {"context", context},
                        {"modes", nlohmann::json::array()}, {"rows", nlohmann::json::array()}};
    char line[512];
    std::snprintf(line, sizeof line,
                  "btflut eval %s: %zu images, hold-out %s (%zu fold(s), %zu predictions per mode), %zu sample pixels\n",
                  dataset.source.c_str(), dataset.images.size(), o.holdout.c_str(), folds.size(), tests, maskPixels);
    std::string text = line;
    std::map<std::string, Direction> lights;  // each held-out image's light, for the rows
    for (const DatasetImage& image : dataset.images) lights[image.name] = image.light;
    std::snprintf(line, sizeof line, "%-30s %7s %7s %7s %6s %9s %9s %8s %9s %8s %8s\n", "mode", "L1", "EMD", "PSNR", "SSIM",
                  "bytes/tx", "GPU B/tx", "bake s", "relight", "frame ms", "GPU-CPU");
    text += line;
    for (const Variant& v : variants) {
        auto mean = [&](double ImageErrors::*field) {
            double sum = 0;
            for (const ImageErrors& e : v.errors) sum += e.*field;
            return v.errors.empty() ? std::nan("") : sum / static_cast<double>(v.errors.size());
        };
        auto meanOf = [](const std::vector<double>& x) {
            double sum = 0;
            for (double d : x) sum += d;
            return x.empty() ? std::nan("") : sum / static_cast<double>(x.size());
        };
        const double l1 = mean(&ImageErrors::l1), emd = mean(&ImageErrors::emd), psnr = mean(&ImageErrors::psnr),
                     ssim = mean(&ImageErrors::ssim), bake = meanOf(v.bakeSeconds),
                     relight = v.relightSeconds.empty() ? std::nan("") : median(v.relightSeconds) * 1e3;
        // A figure a mode has none of (no GL, no bake) is "-", not nan.
        auto cell = [](double x, int width, int decimals, const char* unit = "") {
            char c[64];
            if (std::isfinite(x)) std::snprintf(c, sizeof c, "%*.*f%s", width, decimals, x, unit);
            else std::snprintf(c, sizeof c, "%*s%*s", width, "-", static_cast<int>(std::string(unit).size()), "");
            return std::string(c);
        };
        char name[64];
        std::snprintf(name, sizeof name, "%-30s", v.name.c_str());
        text += std::string(name) + " " + cell(l1, 7, 4) + " " + cell(emd, 7, 4) + " " + cell(psnr, 7, 2) + " " + cell(ssim, 6, 3) +
                " " + cell(v.bytesPerTexel, 9, 2) + " " + cell(v.gpuBytesPerTexel, 9, 2) + " " + cell(bake, 8, 3) + " " +
                cell(relight, 6, 2, " ms") + " " + cell(v.frameMs, 8, 2) + " " + cell(v.gpuMaxDiff, 8, 1) + "\n";
        auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
        json["modes"].push_back({{"name", v.name}, {"mode", v.modeName()}, {"references", v.references},
                                 {"regions", v.regions}, {"colour", colourName(v.colour)}, {"luts_blended", v.blendedLuts}, {"fill", v.filled ? "model" : "clamp"},
                                 {"l1", number(l1)}, {"emd", number(emd)}, {"psnr", number(psnr)}, {"ssim", number(ssim)},
                                 {"bytes_per_texel", v.bytesPerTexel}, {"gpu_bytes_per_texel", number(v.gpuBytesPerTexel)},
                                 {"bake_seconds", number(bake)}, {"relight_ms", number(relight)},
                                 {"frame_ms", number(v.frameMs)}, {"gpu_max_diff_255", number(v.gpuMaxDiff)}});
        for (std::size_t i = 0; i < v.errors.size(); ++i) {
            const Direction light = lights.count(v.images[i]) ? lights.at(v.images[i]) : Direction{};
            json["rows"].push_back({{"image", v.images[i]}, {"mode", v.name}, {"theta", light.thetaDegrees()},
                                    {"phi", light.phiDegrees()}, {"l1", v.errors[i].l1}, {"emd", v.errors[i].emd},
                                    {"psnr", v.errors[i].psnr}, {"ssim", v.errors[i].ssim}});
        }
    }
    text += "L1, EMD: masked 64-bin grey histograms against the photograph's; PSNR (dB, RGB) and SSIM (grey) over the mask;\n"
            "bytes/tx: data per texel a mode draws from (GPU B/tx: as allocated, padding and mipmaps included); bake s per\n"
            "bank; relight: CPU, one light change (LUTs and image); frame ms: GL, 4 quads at 1024x1024, the light moving;\n"
            "GPU-CPU: the largest difference of render --native from relight, in 1/255.\n";
    if (!context.empty()) text += "GL: " + context + "\n";
    return {text, json};
}

Status writeReport(const Report& r, const std::vector<std::vector<SheetCell>>& sheet, const EvalOptions& o) {
    std::error_code ec;
    fs::create_directories(o.output, ec);
    if (ec) return Error{o.output + ": cannot create the folder (" + ec.message() + ")"};
    std::string csv = "image,mode,theta,phi,l1,emd,psnr,ssim\n";
    for (const nlohmann::json& row : r.json["rows"]) {
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%.2f,%.2f,%.6f,%.6f,%.4f,%.5f\n", row["image"].get<std::string>().c_str(),
                      row["mode"].get<std::string>().c_str(), row["theta"].get<double>(), row["phi"].get<double>(),
                      row["l1"].get<double>(), row["emd"].get<double>(), row["psnr"].get<double>(), row["ssim"].get<double>());
        csv += line;
    }
    const std::string jsonText_ = jsonText(r.json);
    const Bytes png = encodePng(contactSheet(sheet, 192), 8);
    const std::string dir = o.output;
    if (Status s = writeFilesAtomically({{dir + "/eval.txt", r.text.data(), r.text.size()},
                                         {dir + "/eval.json", jsonText_.data(), jsonText_.size()},
                                         {dir + "/rows.csv", csv.data(), csv.size()},
                                         {dir + "/contact.png", png.data(), png.size()}});
        !s)
        return s;
    return success();
}

}  // namespace btflut::cli::eval
