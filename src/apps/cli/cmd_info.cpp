// btflut info: what a bank holds.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/bake/target_choice.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "core/predict/model_predictor.h"
#include "core/predict/reference_blend.h"
#include "core/relight/relighter.h"

namespace btflut::cli {

namespace {

struct InfoOptions {
    std::string bank;
    bool json = false;
    bool quiet = false;
    bool verbose = false;  ///< the validation tables too
};

std::string fixed(double v, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

// How bake --predictor auto chose: each candidate's validation figures at its best match
// strength within the L1 rule, and the choice.
void printSelection(const std::string& selection, bool verbose) {
    const nlohmann::json s = nlohmann::json::parse(selection, nullptr, false);
    if (!s.is_object() || !s.contains("chosen")) return;
    const nlohmann::json& chosen = s["chosen"];
    std::cout << "  chosen:    " << chosen.value("name", std::string("?")) << ", match "
              << fixed(chosen.value("match", 1.0), 2) << ", " << chosen.value("bytes", 0) << " bytes per texel"
              << (chosen.contains("multiply_adds")
                      ? ", " + std::to_string(chosen["multiply_adds"].get<std::size_t>()) + " multiply-adds a texel"
                      : std::string())
              << ", by validation on " << s.value("folds", 0)
              << " fold(s) of the dataset's own lights within a budget of " << s.value("budget", 0) << " bytes"
              << (s.contains("decode_budget")
                      ? " and " + std::to_string(s["decode_budget"].get<std::size_t>()) + " multiply-adds"
                      : std::string())
              << " (" << s.value("rule", std::string()) << ")\n";
    if (s.contains("note")) std::cout << "             " << s["note"].get<std::string>() << "\n";
    if (!s.contains("candidates") || !s["candidates"].is_array()) return;
    if (!verbose) {
        std::cout << "             (each of the " << s["candidates"].size()
                  << " candidates' validation: btflut info --verbose)\n";
        return;
    }
    std::cout << "             candidate   bytes  mult-adds  match   PSNR      L1\n";
    for (const nlohmann::json& c : s["candidates"]) {
        const std::string name = c.value("name", std::string("?"));
        // Multiply-adds per texel: banks baked before they were recorded say "-".
        const std::string macs =
            c.contains("multiply_adds") ? std::to_string(c["multiply_adds"].get<std::size_t>()) : "-";
        char line[300];
        if (c.contains("skipped")) {
            std::snprintf(line, sizeof line, "             %-10s %6d  %9s  %s\n", name.c_str(), c.value("bytes", 0),
                          macs.c_str(), c["skipped"].get<std::string>().c_str());
            std::cout << line;
            continue;
        }
        for (const nlohmann::json& v : c.value("validation", nlohmann::json::array())) {
            std::snprintf(line, sizeof line, "             %-10s %6d  %9s  %5.2f  %5.2f  %6.4f\n", name.c_str(),
                          c.value("bytes", 0), macs.c_str(), v.value("match", 1.0), v.value("psnr", 0.0),
                          v.value("l1", 0.0));
            std::cout << line;
        }
    }
}

// How the targets are estimated between the measured lights: the choice, and each
// candidate's validation L1 in the first layer (per region).
void printTargetChoice(const LutBank& b, bool verbose) {
    const nlohmann::json s = nlohmann::json::parse(b.targetChoice, nullptr, false);
    std::cout << "  between:   " << targetChoiceSummary(b);
    if (!s.is_object() || !s.contains("layers") || !s["layers"].is_array() || s["layers"].empty()) {
        std::cout << "\n";
        return;
    }
    const nlohmann::json& layer = s["layers"][0];
    if (layer.contains("skipped")) {
        std::cout << " (" << layer["skipped"].get<std::string>() << ")\n";
        return;
    }
    const bool pairs = layer.value("domain", std::string()) == "pairs";  // the isotropic domain: one choice
    std::cout << ", by validation: each of the " << layer.value("lights", 0)
              << (pairs ? " measured light and view pairs (points of the isotropic domain)" : " measured lights")
              << " estimated from the others (" << layer.value("folds", 0) << " folds; "
              << s.value("rule", std::string()) << ")\n";
    // The rough-surface model behind the "model" candidates: its fit, or why there is none.
    if (const nlohmann::json& m = s.value("model", nlohmann::json()); m.contains("roughness"))
        std::cout << "             model: lambert rough surface fitted to the measured histograms, r "
                  << fixed(m.value("roughness", 0.0), 3) << ", gain " << fixed(m.value("gain", 0.0), 3) << ", rms "
                  << fixed(m.value("rms", 0.0), 4) << "\n";
    else if (m.contains("error"))
        std::cout << "             model: not a candidate (" << m.value("error", std::string()) << ")\n";
    const nlohmann::json candidates = layer.value("candidates", nlohmann::json::array());
    if (!verbose) {
        std::cout << "             (each of the " << candidates.size()
                  << " estimates' validation L1: btflut info --verbose)\n";
        return;
    }
    if (s["layers"].size() > 1) std::cout << "             layer 0 of " << s["layers"].size() << ":\n";
    std::cout << "             estimate                     L1 (64 bins) per region\n";
    for (const nlohmann::json& c : candidates) {
        char line[64];
        std::snprintf(line, sizeof line, "             %-26s", c.value("name", std::string("?")).c_str());
        std::cout << line;
        // A fit with more terms than the folds' lights allow (two a term) is not a candidate.
        const nlohmann::json l1s = c.value("l1", nlohmann::json::array());
        if (std::none_of(l1s.begin(), l1s.end(), [](const nlohmann::json& l1) { return l1.is_number(); }))
            std::cout << "  not fitted: more terms than two lights a term allow";
        for (const nlohmann::json& l1 : l1s)
            if (l1.is_number()) std::cout << "  " << fixed(l1.get<double>(), 4);
        std::cout << "\n";
    }
}

std::string degrees(Direction d) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", d.thetaDegrees(), d.phiDegrees());
    return buf;
}

// What a view layer holds: its nodes, and its grid nodes in the hemisphere by provenance.
struct LayerSummary {
    std::size_t measured = 0, modelled = 0;
    double maxTheta = 0;                  ///< of the measured lights
    std::size_t cells[4] = {0, 0, 0, 0};  ///< by Provenance
};

LayerSummary summarise(const LutBank& b, const ViewLayer& layer) {
    LayerSummary out;
    for (int j = 0; j < b.gridSize; ++j)
        for (int i = 0; i < b.gridSize; ++i) {
            DiskPoint p = b.gridPoint(i, j);
            if (p.x * p.x + p.y * p.y > 1) continue;  // beyond the horizon
            ++out.cells[static_cast<int>(layer.gridProvenance[static_cast<std::size_t>(j) * b.gridSize + i])];
        }
    for (const LightNode& n : layer.nodes) {
        (n.modelled ? out.modelled : out.measured) += 1;
        if (!n.modelled) out.maxTheta = std::max(out.maxTheta, n.light.thetaDegrees());
    }
    return out;
}

nlohmann::json infoJson(const std::string& path, const LutBank& b) {
    nlohmann::json out{{"file", path},
                       {"format_version", bankFormatVersion(b)},
                       {"bytes", std::filesystem::file_size(path)},
                       {"entries", b.entries},
                       {"colour", colourName(b.colour)},
                       {"grid_size", b.gridSize},
                       {"domain", domainName(b.domain)},
                       {"reference",
                        {{"name", b.referenceName},
                         {"light", directionJson(b.referenceLight)},
                         {"view", directionJson(b.referenceView)},
                         {"width", b.reference.width},
                         {"height", b.reference.height},
                         {"channels", b.reference.channels},
                         {"bit_depth", b.reference.bitDepth},
                         {"embedded", !b.reference.samples.empty()}}},
                       {"ptm", !b.ptm.empty()},
                       {"layers", nlohmann::json::array()}};
    if (b.makesLuts()) {
        const ReferenceBlend* references = b.predictorAs<ReferenceBlend>();
        out["blend"] = {
            {"predictor", b.predictorName()},
            {"references", references ? references->references().size() : 0},
            {"regions", b.prediction.regions},
            {"quantiles", b.prediction.quantiles},
            {"match", b.prediction.match},
            {"target", b.prediction.target == LutBank::Prediction::Target::Corrections ? "corrections" : "measured"},
            {"bytes_per_texel", b.predictorBytesPerTexel()},
            {"multiply_adds_per_texel", b.predictor().multiplyAdds()}};
        if (const ModelPredictor* model = b.predictorAs<ModelPredictor>()) {
            const LightModel& m = model->model();
            out["blend"]["model"] = {{"basis", lightBasisName(m.basis)},
                                     {"planes", m.planes},
                                     {"channels", m.channels},
                                     {"albedo", !m.albedo.empty()},
                                     {"bytes_per_texel", m.bytesPerTexel()}};
        }
    }
    if (!b.selection.empty()) out["selection"] = nlohmann::json::parse(b.selection, nullptr, false);
    if (!b.targetChoice.empty()) out["target_choice"] = nlohmann::json::parse(b.targetChoice, nullptr, false);
    if (!b.modelFill.empty()) out["model_fill"] = nlohmann::json::parse(b.modelFill, nullptr, false);
    for (std::size_t l = 0; l < b.layers.size(); ++l) {
        const LayerSummary s = summarise(b, b.layers[l]);
        out["layers"].push_back({{"view", directionJson(b.layers[l].view)},
                                 {"light_nodes", s.measured},
                                 {"modelled_nodes", s.modelled},
                                 {"max_theta", s.maxTheta},
                                 {"grid_measured", s.cells[0]},
                                 {"grid_interpolated", s.cells[1]},
                                 {"grid_clamped", s.cells[2]},
                                 {"grid_modelled", s.cells[3]},
                                 {"coverage", b.lightCoverage(l)}});
    }
    return out;
}

Status runInfo(const InfoOptions& o) {
    Result<LutBank> bank = loadBank(o.bank);
    if (!bank) return Error{bank.error()};
    if (o.quiet) return success();  // the bank reads, every chunk checked: exit 0
    const LutBank& b = *bank;
    if (o.json) {
        std::cout << jsonText(infoJson(o.bank, b));
        return success();
    }
    std::cout << o.bank << ": btflut bank, format version " << bankFormatVersion(b) << ", "
              << std::filesystem::file_size(o.bank) << " bytes\n"
              << "  LUTs:      " << b.entries << " entries, "
              << (b.colour == ColourMode::Grey  ? "grey (one LUT on the grey value)"
                  : b.colour == ColourMode::Rgb ? "rgb (one LUT per channel)"
                                                : "lrgb (one LUT on the grey value, the albedo's chroma)")
              << "\n  reference: " << b.referenceName << ", light " << degrees(b.referenceLight) << ", view "
              << degrees(b.referenceView) << ", ";
    std::cout << b.reference.width << "x" << b.reference.height << "x" << b.reference.channels << " "
              << b.reference.bitDepth << "-bit, " << (b.reference.samples.empty() ? "not embedded" : "embedded")
              << "\n";
    if (b.makesLuts()) {
        // "relit per light" only: how far it is matched is the next line's (0: not at all).
        std::cout << "  predictor: " << b.predictor().description() << ", LUTs made at run time from ";
        std::cout << b.prediction.quantiles << "-sample quantile functions; " << b.prediction.regions << " region(s)";
        if (b.prediction.regions > 1) {
            std::vector<std::size_t> texels(static_cast<std::size_t>(b.prediction.regions), 0);
            for (std::size_t i = 0; i < b.prediction.labels.size(); ++i)
                texels[b.prediction.labels[i]] += b.prediction.mask.inside[i];
            std::cout << " (sample pixels:";
            for (std::size_t n : texels) std::cout << " " << n;
            std::cout << ")";
        }
        std::cout << "\n  match:     "
                  << (b.prediction.match == 1
                          ? std::string("fully")
                          : "fully at the measured lights; " +
                                (b.prediction.match == 0
                                     ? std::string("away from them not at all (the prediction as it is)")
                                     : fixed(b.prediction.match, 2) + " of the way to the target away from them") +
                                " (ramped over " + fixed(matchRampRadius(b), 3) + " of the light disk)")
                  << (b.prediction.target == LutBank::Prediction::Target::Corrections
                          ? ", through the nodes' corrections blended at the light"
                          : ", to the measured distributions: at a measured light its own, between them " +
                                std::string(targetChoiceSummary(b) == "blend"
                                                ? "their blend"
                                                : "their blend corrected by a fit over the light (below)"))
                  << "\n";
        printTargetChoice(b, o.verbose);
        if (const ReferenceBlend* references = b.predictorAs<ReferenceBlend>())
            for (std::size_t k = 0; k < references->lights().size(); ++k)
                std::cout << "    reference " << k << ": " << references->lights()[k].name << ", light "
                          << degrees(references->lights()[k].light) << "\n";
    }
    if (!b.selection.empty()) printSelection(b.selection, o.verbose);
    if (!b.makesLuts()) printTargetChoice(b, o.verbose);
    if (!b.ptm.empty())
        std::cout << "  ptm: " << b.ptm.width << "x" << b.ptm.height << ", 6 coefficients + RGB albedo per texel ("
                  << b.ptm.coefficients.size() + b.ptm.albedo.size() << " bytes)\n";
    if (!b.modelFill.empty())
        std::cout << "  model:     directions without measurements filled from " << b.modelFill << "\n";
    std::cout << "  grid:      " << b.gridSize << "x" << b.gridSize
              << " nodes per view layer over the equal-area light disk\n"
              << "  layers:    " << b.layers.size() << " view direction(s)\n"
              << "  domain:    " << domainName(b.domain)
              << (b.domain == BankDomain::Layers
                      ? " (over each layer's lights, then between the layers' views)\n"
                      : " (over theta_i, theta_r and phi_i - phi_r: an isotropic material)\n");
    for (std::size_t l = 0; l < b.layers.size(); ++l) {
        const ViewLayer& layer = b.layers[l];
        const LayerSummary summary = summarise(b, layer);
        const std::size_t* counts = summary.cells;
        const std::size_t modelled = summary.modelled;
        const double maxTheta = summary.maxTheta;
        // The share of light directions (by solid angle) where lookups interpolate; a grid
        // too coarse to have nodes inside the hemisphere (--grid 2) still has a coverage.
        char line[400];
        std::snprintf(line, sizeof line,
                      "  layer %zu: view %s, %zu light nodes (theta up to %.1f)%s, grid nodes in the "
                      "hemisphere: %zu measured, %zu interpolated, %zu modelled, %zu clamped; %.0f%% of light "
                      "directions covered by measurements%s\n",
                      l, degrees(layer.view).c_str(), layer.nodes.size() - modelled, maxTheta,
                      modelled ? (" + " + std::to_string(modelled) + " modelled").c_str() : "", counts[0], counts[1],
                      counts[3], counts[2], 100.0 * b.lightCoverage(l), modelled ? ", the rest modelled" : "");
        std::cout << line;
        if (counts[2] > 0 && !modelled && b.lightCoverage(l) < 0.5)
            std::cout << "    note: lights beyond theta " << fixed(maxTheta, 1)
                      << " are clamped to the nearest measured edge's LUT (wrong shadows and speckle far from it); "
                         "`bake --fill model` fills them from the fitted rough-surface model\n";
    }
    return success();
}

}  // namespace

void addInfoCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<InfoOptions>();
    CLI::App* app = root.add_subcommand("info", "Describe a LUT bank: header, grid, coverage, size");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_flag("--json", o->json, "print JSON (everything, the validation tables included)");
    app->add_flag("--verbose", o->verbose,
                  "also the validation tables: each candidate predictor's and each estimate of the targets'");
    addQuietFlag(
        *app, o->quiet,
        "print nothing: exit 0 when the bank reads whole, non-zero with one line when not (a check for scripts)");
    commands.push_back({app, [o] { return runInfo(*o); }});
}

}  // namespace btflut::cli
