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

// Each mode's mean PSNR and L1 against what it costs (bytes per texel, multiply-adds per texel,
// relight and frame time),
// one labelled point per mode and setting, the Pareto fronts drawn and listed in the JSON.
void addTradeoff(Report& r) {
    struct Cost {
        const char* key;
        const char* label;
        const char* axis;
    };
    static const Cost kCosts[] = {{"bytes_per_texel", "bytes per texel", "bytes per texel"},
                                  {"multiply_adds_per_texel", "decoding", "multiply-adds per texel (a moving light)"},
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
            ChartPanel panel{.title = std::string(f.label) + " against " + c.label,
                             .xLabel = c.axis,
                             .yLabel = f.better == Better::Higher ? "dB, higher is better" : "lower is better",
                             .logX = true,
                             .pareto = f.better};
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

// The 10-degree band of theta a light falls in: bands centred on multiples of 10, so a dome's
// rings (at 20, 40, 60, 80 degrees, give or take a measurement's error) sit in the middle of
// theirs rather than on an edge, split between two.
int thetaBand(double theta) { return static_cast<int>(std::floor(theta / 10 + 0.5)); }

// Each mode's mean PSNR and L1 over the held-out lights in 10-degree bands of theta: where
// each mode fails.
void addByTheta(Report& r) {
    constexpr double kBand = 10;
    std::map<std::string, std::map<int, std::vector<const nlohmann::json*>>> rows;  // mode, band
    std::vector<std::string> modes;
    for (const nlohmann::json& m : r.json["modes"]) modes.push_back(m["name"]);
    for (const nlohmann::json& row : r.json["rows"])
        rows[row["mode"]][thetaBand(row["theta"].get<double>())].push_back(&row);
    nlohmann::json out{{"band_degrees", kBand}, {"modes", nlohmann::json::array()}};
    ChartPanel psnr{.title = "PSNR against the light's theta",
                    .xLabel = "theta (degrees), 10-degree bands",
                    .yLabel = "dB",
                    .lines = true};
    ChartPanel l1{.title = "histogram L1 against the light's theta",
                  .xLabel = "theta (degrees), 10-degree bands",
                  .yLabel = "L1",
                  .lines = true};
    for (const std::string& name : modes) {
        nlohmann::json mode{{"name", name},
                            {"theta", nlohmann::json::array()},
                            {"psnr", nlohmann::json::array()},
                            {"l1", nlohmann::json::array()},
                            {"count", nlohmann::json::array()}};
        ChartSeries p{name, {}, {}}, l{name, {}, {}};
        for (const auto& [band, members] : rows[name]) {
            double sumPsnr = 0, sumL1 = 0;
            for (const nlohmann::json* row : members)
                sumPsnr += (*row)["psnr"].is_number() ? (*row)["psnr"].get<double>() : std::nan(""),
                    sumL1 += (*row)["l1"].get<double>();
            const double n = static_cast<double>(members.size()), centre = band * kBand;
            mode["theta"].push_back(centre);
            mode["psnr"].push_back(std::isfinite(sumPsnr) ? nlohmann::json(sumPsnr / n) : nlohmann::json(nullptr));
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

// A mode's mean error over its predictions inside (0), outside (1) the hull, or all (-1); NaN
// for none, and for pixel figures where pixels are not compared.
double meanError(const Variant& v, double ImageErrors::*field, bool pixels, int where = -1) {
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < v.errors.size(); ++i)
        if (where < 0 || static_cast<int>(v.outside[i]) == where) sum += v.errors[i].*field, ++n;
    const bool pixel = field == &ImageErrors::psnr || field == &ImageErrors::ssim;
    return n == 0 || (pixel && !pixels) ? std::nan("") : sum / static_cast<double>(n);
}

nlohmann::json numberOrNull(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

double meanOf(const std::vector<double>& x) {
    double sum = 0;
    for (double d : x) sum += d;
    return x.empty() ? std::nan("") : sum / static_cast<double>(x.size());
}

// The mean of the finite values; NaN when there are none.
double meanOfFinite(const std::vector<double>& x) {
    double sum = 0;
    std::size_t n = 0;
    for (double t : x)
        if (std::isfinite(t)) sum += t, ++n;
    return n ? sum / static_cast<double>(n) : std::nan("");
}

// A table cell: a figure a mode has none of (no GL, no bake) is "-", not nan.
std::string cell(double x, int width, int decimals, const char* unit = "") {
    char c[64];
    if (std::isfinite(x))
        std::snprintf(c, sizeof c, "%*.*f%s", width, decimals, x, unit);
    else
        std::snprintf(c, sizeof c, "%*s%*s", width, "-", static_cast<int>(std::string(unit).size()), "");
    return std::string(c);
}

// Beside each mean its spread over the predictions: the per-image standard deviation and the
// 95% interval of the mean (normal approximation, mean +- 1.96 sd / sqrt(n)), so two modes'
// figures can be told apart from the noise of which images were held out.
nlohmann::json spreadOf(const Variant& v, bool pixels) {
    nlohmann::json spread;
    for (const auto& [key, field] : {std::pair{"l1", &ImageErrors::l1}, std::pair{"emd", &ImageErrors::emd},
                                     std::pair{"psnr", &ImageErrors::psnr}, std::pair{"ssim", &ImageErrors::ssim}}) {
        const double m = meanError(v, field, pixels);
        const std::size_t n = v.errors.size();
        if (!std::isfinite(m) || n < 2) {
            spread[key] = nullptr;
            continue;
        }
        double squares = 0;
        for (const ImageErrors& e : v.errors) squares += (e.*field - m) * (e.*field - m);
        const double sd = std::sqrt(squares / static_cast<double>(n - 1)),
                     half = 1.96 * sd / std::sqrt(static_cast<double>(n));
        spread[key] = {{"sd", numberOrNull(sd)}, {"ci95", {numberOrNull(m - half), numberOrNull(m + half)}}};
    }
    return spread;
}

// A row per held-out prediction of the mode.
void addRows(nlohmann::json& rows, const Variant& v, const std::map<std::string, const DatasetImage*>& byName,
             bool pixels) {
    for (std::size_t i = 0; i < v.errors.size(); ++i) {
        const DatasetImage& image = *byName.at(v.images[i]);
        rows.push_back({{"image", v.images[i]},
                        {"mode", v.name},
                        {"theta", image.light.thetaDegrees()},
                        {"phi", image.light.phiDegrees()},
                        {"view_theta", image.view.thetaDegrees()},
                        {"view_phi", image.view.phiDegrees()},
                        {"outside_hull", static_cast<bool>(v.outside[i])},
                        {"l1", v.errors[i].l1},
                        {"target_l1", i < v.targetL1.size() ? numberOrNull(v.targetL1[i]) : nlohmann::json()},
                        {"emd", v.errors[i].emd},
                        {"psnr", pixels ? nlohmann::json(v.errors[i].psnr) : nlohmann::json(nullptr)},
                        {"ssim", pixels ? nlohmann::json(v.errors[i].ssim) : nlohmann::json(nullptr)}});
    }
}

// The run's head: the dataset, the protocol and the options that made the figures (so a run
// can be repeated and compared), with empty lists of modes and rows.
nlohmann::json runJson(const Dataset& dataset, const EvalOptions& o, std::size_t folds, std::size_t tests,
                       std::size_t maskPixels, const std::string& context) {
    return {{"dataset", dataset.source},
            {"images", dataset.images.size()},
            {"holdout", o.holdout},
            {"folds", folds},
            {"held_out", tests},
            {"mask_pixels", maskPixels},
            {"context", context},
            {"modes", nlohmann::json::array()},
            {"rows", nlohmann::json::array()},
            {"fixed_view", dataset.fixedView()},
            {"rectified", dataset.rectified},
            // What made these figures, so a run can be repeated and compared.
            {"btflut_version", BTFLUT_VERSION},
            {"options",
             {{"holdout", o.holdout},
              {"modes", o.modes},
              {"references", o.references},
              {"regions", o.regions},
              {"colour", o.colours},
              {"predictor", o.predictors},
              {"fill", o.fills},
              {"target", o.targets},
              {"mask", o.mask},
              {"grid", o.grids},
              {"luts", o.lutSources},
              {"domain", o.domains},
              {"match", o.matches},
              {"budget", o.budgets},
              {"blended_luts", o.blendedLuts},
              {"gl", !o.noGl},
              {"backend", o.backend},
              {"frames", o.frames}}}};
}

// Each mode's L1 and EMD inside and outside the measured hull of its bank's domain.
std::string hullTable(const nlohmann::json& modes) {
    std::string text = "\ninside and outside the measured hull of each bank's domain: L1, EMD (predictions)\n";
    for (const nlohmann::json& m : modes) {
        auto figure = [](const nlohmann::json& x) { return x.is_number() ? x.get<double>() : std::nan(""); };
        char row[256];
        std::string cells;
        for (const char* where : {"inside_hull", "outside_hull"}) {
            const nlohmann::json& part = m[where];
            char c[96];
            if (part["count"] == 0)
                std::snprintf(c, sizeof c, "  %-8s %7s %7s (0)", where[0] == 'i' ? "inside" : "outside", "-", "-");
            else
                std::snprintf(c, sizeof c, "  %-8s %7.4f %7.4f (%zu)", where[0] == 'i' ? "inside" : "outside",
                              figure(part["l1"]), figure(part["emd"]), part["count"].get<std::size_t>());
            cells += c;
        }
        std::snprintf(row, sizeof row, "%-30s%s\n", m["name"].get<std::string>().c_str(), cells.c_str());
        text += row;
    }
    text += "\n";
    return text;
}

// What the table's columns and names mean.
constexpr const char* kLegend =
    "L1, EMD: masked 64-bin grey histograms against the photograph's; PSNR (dB, RGB) and SSIM (grey) over the mask;\n"
    "bytes/tx: data per texel a mode draws from (GPU B/tx: as allocated, padding and mipmaps included); bake s per\n"
    "bank; relight: CPU, one light change (LUTs and image); frame ms: GL, 4 quads at 1024x1024, the light moving;\n"
    "GPU-CPU: the largest difference of render --native from relight, in 1/255.\n"
    "Names: lut K<k> R<r> <colour>: a bank of k references blended per light (K1: the paper's bank), its sample in\n"
    "r regions matched apart (--regions), colour grey, rgb or lrgb; lut auto: bake's validated choice; lut <basis>: a\n"
    "light model (ptm, hsh2, rbf9, ...) matched; ptm, hsh, rbf, bln alone: the light model unmatched, as RTI viewers "
    "draw it.\n";

}  // namespace

Report report(const std::vector<Variant>& variants, const Dataset& dataset, const EvalOptions& o,
              const std::vector<Fold>& folds, std::size_t maskPixels, const std::string& context) {
    std::size_t tests = 0;
    for (const Fold& f : folds) tests += f.test.size();
    nlohmann::json json = runJson(dataset, o, folds.size(), tests, maskPixels, context);
    // Pixels compare where every image shares one frame: a fixed camera, or a rectified BTF.
    const bool pixels = dataset.fixedView() || dataset.rectified;
    if (!pixels) json["pixels"] = "not compared: the views' images are not rectified to one frame (PSNR, SSIM null)";
    char line[512];
    std::snprintf(
        line, sizeof line,
        "btflut eval %s: %zu images, hold-out %s (%zu fold(s), %zu predictions per mode), %zu sample pixels\n",
        dataset.source.c_str(), dataset.images.size(), o.holdout.c_str(), folds.size(), tests, maskPixels);
    std::string text = line;
    std::string chosenText;                             // lut auto's choice per fold, after the table
    std::string trainingText;                           // neuralrti's training per fold
    std::string targetText;                             // the targets' own L1, after the table
    std::map<std::string, const DatasetImage*> byName;  // each held-out image's light and view, for the rows
    for (const DatasetImage& image : dataset.images) byName[image.name] = &image;
    std::snprintf(line, sizeof line, "%-30s %7s %7s %7s %6s %9s %9s %8s %9s %8s %8s\n", "mode", "L1", "EMD", "PSNR",
                  "SSIM", "bytes/tx", "GPU B/tx", "bake s", "relight", "frame ms", "GPU-CPU");
    text += line;
    for (const Variant& v : variants) {
        auto mean = [&](double ImageErrors::*field, int where = -1) { return meanError(v, field, pixels, where); };
        const double l1 = mean(&ImageErrors::l1), emd = mean(&ImageErrors::emd), psnr = mean(&ImageErrors::psnr),
                     ssim = mean(&ImageErrors::ssim), bake = meanOf(v.bakeSeconds),
                     relight = v.relightSeconds.empty() ? std::nan("") : median(v.relightSeconds) * 1e3;
        // Banked modes: the folds' mean (lut auto may choose a predictor of another size per fold).
        const double bytes = v.foldBytesPerTexel.empty() ? v.bytesPerTexel : meanOf(v.foldBytesPerTexel),
                     multiplyAdds = v.foldMultiplyAdds.empty() ? v.multiplyAdds : meanOf(v.foldMultiplyAdds);
        char name[64];
        std::snprintf(name, sizeof name, "%-30s", v.name.c_str());
        text += std::string(name) + " " + cell(l1, 7, 4) + " " + cell(emd, 7, 4) + " " + cell(psnr, 7, 2) + " " +
                cell(ssim, 6, 3) + " " + cell(bytes, 9, 2) + " " + cell(v.gpuBytesPerTexel, 9, 2) + " " +
                cell(bake, 8, 3) + " " + cell(relight, 6, 2, " ms") + " " + cell(v.frameMs, 8, 2) + " " +
                cell(v.gpuMaxDiff, 8, 1) + "\n";
        json["modes"].push_back({{"name", v.name},
                                 {"mode", v.modeName()},
                                 {"domain", domainName(v.bankDomain)},
                                 {"references", v.references},
                                 {"regions", v.regions},
                                 {"colour", colourName(v.colour)},
                                 {"luts_blended", v.blendedLuts},
                                 {"fill", v.filled ? "model" : "clamp"},
                                 {"l1", numberOrNull(l1)},
                                 {"emd", numberOrNull(emd)},
                                 {"psnr", numberOrNull(psnr)},
                                 {"ssim", numberOrNull(ssim)},
                                 {"bytes_per_texel", bytes},
                                 {"bytes_per_texel_by_fold", v.foldBytesPerTexel},
                                 {"multiply_adds_per_texel", multiplyAdds},
                                 {"gpu_bytes_per_texel", numberOrNull(v.gpuBytesPerTexel)},
                                 {"bake_seconds", numberOrNull(bake)},
                                 {"relight_ms", numberOrNull(relight)},
                                 {"frame_ms", numberOrNull(v.frameMs)},
                                 {"gpu_max_diff_255", numberOrNull(v.gpuMaxDiff)}});
        const auto outside = static_cast<std::size_t>(std::count(v.outside.begin(), v.outside.end(), true));
        nlohmann::json& mode = json["modes"].back();
        // The target's own L1 beside the mode's: the histogram estimate's error apart from the match's.
        const double target = meanOfFinite(v.targetL1);
        mode["target_l1"] = numberOrNull(target);
        if (std::isfinite(target)) {
            char row[160];
            std::snprintf(row, sizeof row, "  %-30s target %6.4f   relit %6.4f\n", v.name.c_str(), target, l1);
            targetText += row;
        }
        if (!v.chosen.empty()) {  // lut auto: what bake chose in each fold
            mode["chosen"] = v.chosen;
            chosenText += "  " + v.name + ":";
            for (std::size_t f = 0; f < v.chosen.size(); ++f)
                chosenText += (f ? ", " : " ") + std::string("fold ") + std::to_string(f + 1) + " " + v.chosen[f];
            chosenText += "\n";
        }
        if (!v.training.empty()) {  // neuralrti: how each fold's training went
            mode["training"] = v.training;
            for (std::size_t f = 0; f < v.training.size(); ++f)
                trainingText += "  " + v.name + " fold " + std::to_string(f + 1) + ": " + v.training[f] + "\n";
        }
        mode["spread"] = spreadOf(v, pixels);
        for (int where : {0, 1})
            mode[where ? "outside_hull" : "inside_hull"] = {{"count", where ? outside : v.errors.size() - outside},
                                                            {"l1", numberOrNull(mean(&ImageErrors::l1, where))},
                                                            {"emd", numberOrNull(mean(&ImageErrors::emd, where))},
                                                            {"psnr", numberOrNull(mean(&ImageErrors::psnr, where))}};
        addRows(json["rows"], v, byName, pixels);
    }
    if (!targetText.empty())
        text +=
            "\nhistogram L1 of each bank's target at the held-out lights (its estimate of the histogram there)\n"
            "against the photographs', beside the relit image's:\n" +
            targetText;
    if (!chosenText.empty())
        text += "\nlut auto chose, per fold (bake's validation on the fold's training lights):\n" + chosenText;
    if (!trainingText.empty()) text += "\nNeuralRTI's training (its own 10% of pairs validating):\n" + trainingText;
    // Bins outside the measured hull (the bank clamped or modelled them) apart from those inside.
    const bool anyOutside = std::any_of(json["modes"].begin(), json["modes"].end(),
                                        [](const nlohmann::json& m) { return m["outside_hull"]["count"] > 0; });
    // Every held-out image outside the hull (curet-c2's sparse pairs): the table measures
    // extrapolation alone, which a reader must be told before reading it as interpolation.
    const bool allOutside =
        !json["modes"].empty() && std::all_of(json["modes"].begin(), json["modes"].end(), [](const nlohmann::json& m) {
            return m["inside_hull"]["count"] == 0 && m["outside_hull"]["count"] > 0;
        });
    if (allOutside) {
        const std::string note =
            "every held-out image lies outside the hull of its fold's training lights (and views): the figures "
            "measure extrapolation only; hold out fewer, or capture denser";
        text = "note: " + note + "\n" + text;
        json["note"] = note;
    }
    if (anyOutside || !dataset.fixedView()) text += hullTable(json["modes"]);
    text += kLegend;
    if (!context.empty()) text += "GL: " + context + "\n";
    Report r{text, json, {}, {}};
    addTradeoff(r);
    addByTheta(r);
    return r;
}

Status writeReport(const Report& r, const std::vector<std::vector<SheetCell>>& sheet,
                   const std::vector<PlotColumn>& sheetHistograms, const EvalOptions& o) {
    std::error_code ec;
    fs::create_directories(o.output, ec);
    if (ec) return Error{o.output + ": cannot create the folder (" + ec.message() + ")"};
    // A figure the rows have none of (PSNR and SSIM of unrectified views) is an empty field.
    auto field = [](const nlohmann::json& x, const char* format) {
        char c[32] = "";
        if (x.is_number()) std::snprintf(c, sizeof c, format, x.get<double>());
        return std::string(c);
    };
    std::string csv = "image,mode,theta,phi,view_theta,view_phi,outside_hull,l1,emd,psnr,ssim\n";
    for (const nlohmann::json& row : r.json["rows"])
        csv += row["image"].get<std::string>() + "," + row["mode"].get<std::string>() + "," +
               field(row["theta"], "%.2f") + "," + field(row["phi"], "%.2f") + "," + field(row["view_theta"], "%.2f") +
               "," + field(row["view_phi"], "%.2f") + "," + (row["outside_hull"].get<bool>() ? "1" : "0") + "," +
               field(row["l1"], "%.6f") + "," + field(row["emd"], "%.6f") + "," + field(row["psnr"], "%.4f") + "," +
               field(row["ssim"], "%.5f") + "\n";
    const std::string jsonText_ = jsonText(r.json);
    const Bytes png = encodePng(contactSheet(sheet, 192), 8), tradeoff = encodePng(drawCharts(r.tradeoff, 3), 8),
                byTheta = encodePng(drawCharts(r.byTheta, 1), 8),
                histograms = encodePng(
                    plotHistograms(sheetHistograms,
                                   {.layout = PlotStyle::Layout::AgainstFirst, .panelWidth = 320, .panelHeight = 120}),
                    8);
    const std::string dir = o.output;
    if (Status s = writeFilesAtomically({{dir + "/eval.txt", r.text.data(), r.text.size()},
                                         {dir + "/eval.json", jsonText_.data(), jsonText_.size()},
                                         {dir + "/rows.csv", csv.data(), csv.size()},
                                         {dir + "/contact.png", png.data(), png.size()},
                                         {dir + "/histograms.png", histograms.data(), histograms.size()},
                                         {dir + "/tradeoff.png", tradeoff.data(), tradeoff.size()},
                                         {dir + "/error_theta.png", byTheta.data(), byTheta.size()}});
        !s)
        return s;
    return success();
}

}  // namespace btflut::cli::eval
