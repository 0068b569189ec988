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

namespace {

// Each mode's mean PSNR and L1 against what it costs (bytes per texel, relight and frame time),
// one labelled point per mode and setting, the Pareto fronts drawn and listed in the JSON.
void addTradeoff(Report& r) {
    struct Cost {
        const char* key;
        const char* label;
        const char* axis;
    };
    static const Cost kCosts[] = {{"bytes_per_texel", "bytes per texel", "bytes per texel"},
                                  {"relight_ms", "relight time", "relight ms (CPU, one light change)"},
                                  {"frame_ms", "frame time", "frame ms (GL, the light moving)"}};
    struct Figure {
        const char* key;
        const char* label;
        Better better;
    };
    static const Figure kFigures[] = {{"psnr", "PSNR", Better::Higher}, {"l1", "histogram L1", Better::Lower}};
    auto value = [](const nlohmann::json& m, const char* key) {
        return m[key].is_number() ? m[key].get<double>() : std::nan("");
    };
    nlohmann::json fronts = nlohmann::json::object();
    for (const Figure& f : kFigures)
        for (const Cost& c : kCosts) {
            ChartPanel panel{.title = std::string(f.label) + " against " + c.label, .xLabel = c.axis,
                             .yLabel = f.better == Better::Higher ? "dB, higher is better" : "lower is better",
                             .logX = true, .pareto = f.better};
            std::vector<double> cost, figure;
            for (const nlohmann::json& m : r.json["modes"]) {
                cost.push_back(value(m, c.key));
                figure.push_back(value(m, f.key));
                panel.series.push_back({m["name"].get<std::string>(), {cost.back()}, {figure.back()}});
            }
            nlohmann::json names = nlohmann::json::array();
            for (std::size_t i : paretoFront(cost, figure, f.better)) names.push_back(r.json["modes"][i]["name"]);
            fronts[std::string(f.key) + "_" + c.key] = names;
            r.tradeoff.push_back(std::move(panel));
        }
    r.json["pareto_fronts"] = fronts;  // per figure and cost: the modes on the front, cheapest first
}

// Each mode's mean PSNR and L1 over the held-out lights in 10-degree bands of theta: where
// each mode fails.
void addByTheta(Report& r) {
    constexpr double kBand = 10;
    std::map<std::string, std::map<int, std::vector<const nlohmann::json*>>> rows;  // mode, band
    std::vector<std::string> modes;
    for (const nlohmann::json& m : r.json["modes"]) modes.push_back(m["name"]);
    for (const nlohmann::json& row : r.json["rows"])
        rows[row["mode"]][static_cast<int>(row["theta"].get<double>() / kBand)].push_back(&row);
    nlohmann::json out{{"band_degrees", kBand}, {"modes", nlohmann::json::array()}};
    ChartPanel psnr{.title = "PSNR against the held-out light's theta", .xLabel = "theta (degrees), 10-degree bands",
                    .yLabel = "dB", .lines = true};
    ChartPanel l1{.title = "histogram L1 against the held-out light's theta", .xLabel = "theta (degrees), 10-degree bands",
                  .yLabel = "L1", .lines = true};
    for (const std::string& name : modes) {
        nlohmann::json mode{{"name", name}, {"theta", nlohmann::json::array()}, {"psnr", nlohmann::json::array()},
                            {"l1", nlohmann::json::array()}, {"count", nlohmann::json::array()}};
        ChartSeries p{name, {}, {}}, l{name, {}, {}};
        for (const auto& [band, members] : rows[name]) {
            double sumPsnr = 0, sumL1 = 0;
            for (const nlohmann::json* row : members) sumPsnr += (*row)["psnr"].get<double>(), sumL1 += (*row)["l1"].get<double>();
            const double n = static_cast<double>(members.size()), centre = (band + 0.5) * kBand;
            mode["theta"].push_back(centre);
            mode["psnr"].push_back(sumPsnr / n);
            mode["l1"].push_back(sumL1 / n);
            mode["count"].push_back(members.size());
            p.x.push_back(centre), p.y.push_back(sumPsnr / n);
            l.x.push_back(centre), l.y.push_back(sumL1 / n);
        }
        out["modes"].push_back(mode);
        psnr.series.push_back(std::move(p));
        l1.series.push_back(std::move(l));
    }
    r.json["by_theta"] = out;
    r.byTheta = {std::move(psnr), std::move(l1)};
}

}  // namespace

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
    Report r{text, json, {}, {}};
    addTradeoff(r);
    addByTheta(r);
    return r;
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
    const Bytes png = encodePng(contactSheet(sheet, 192), 8), tradeoff = encodePng(drawCharts(r.tradeoff, 3), 8),
                byTheta = encodePng(drawCharts(r.byTheta, 1), 8);
    const std::string dir = o.output;
    if (Status s = writeFilesAtomically({{dir + "/eval.txt", r.text.data(), r.text.size()},
                                         {dir + "/eval.json", jsonText_.data(), jsonText_.size()},
                                         {dir + "/rows.csv", csv.data(), csv.size()},
                                         {dir + "/contact.png", png.data(), png.size()},
                                         {dir + "/tradeoff.png", tradeoff.data(), tradeoff.size()},
                                         {dir + "/error_theta.png", byTheta.data(), byTheta.size()}});
        !s)
        return s;
    return success();
}

}  // namespace btflut::cli::eval
