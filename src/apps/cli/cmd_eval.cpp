// btflut eval: the held-out protocol as a command. Bakes from the training images, predicts
// every held-out image through the code users run (the Relighter behind `relight` and the GL
// renderer, the PTM, the nearest training image, ...) and compares each with the photograph.
// Its parts are in eval/ (eval.h).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "cli/command.h"
#include "cli/eval/eval.h"
#include "core/io/json_text.h"

namespace btflut::cli {

namespace {

namespace fs = std::filesystem;
using namespace eval;

Status runEval(EvalOptions o) {
    if (!o.output.empty()) {
        std::error_code ec;
        if (fs::exists(o.output, ec) && !fs::is_directory(o.output, ec))
            return Error{o.output + ": exists and is not a folder"};
    }
    if (o.quiet && o.output.empty()) return Error{"-q leaves eval's figures only in -o DIR's files: give -o"};
    Result<Dataset> dataset = openDatasetWithMask(o.dataset, o.mask);
    if (!dataset) return Error{dataset.error()};
    if (Status s = adaptToViews(o, *dataset); !s) return s;  // several views: lut, nearest, brdf
    const bool views = !dataset->fixedView();
    if (views) o.noGl = true;  // the GL figures draw a fixed camera's scene
    Result<std::vector<Variant>> parsed = variantsOf(o);
    if (!parsed) return Error{parsed.error()};
    std::vector<Variant>& variants = *parsed;
    std::size_t minimumTraining = 2;
    bool ptm = false;
    for (const Variant& v : variants) {
        minimumTraining = std::max<std::size_t>(minimumTraining, static_cast<std::size_t>(v.references));
        if (v.mode == RenderMode::Ptm) ptm = true;
        if (v.mode == RenderMode::Ptm || (v.mode == RenderMode::Lut && v.references == 0))
            minimumTraining = std::max<std::size_t>(minimumTraining, 6);
    }
    Result<std::vector<Fold>> folds = holdoutFolds(*dataset, o.holdout, minimumTraining);
    if (!folds) return Error{folds.error()};

    Result<Image> first = loadImage(dataset->images.front().path);
    if (!first) return Error{first.error()};
    Result<Mask> mask = loadDatasetMask(*dataset, first->width, first->height);
    if (!mask) return Error{mask.error()};

    // Banks for the GL figures (fold 0's), in a temporary folder removed at the end.
    std::string pattern = (fs::temp_directory_path() / "btflut-eval-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
        return Error{"cannot create a temporary folder (" + std::string(std::strerror(errno)) + ")"};
    const fs::path scratch = pattern;
    struct Cleanup {
        fs::path path;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(path, ec);
        }
    } cleanup{scratch};
    std::map<std::string, std::string> bankFiles;

    std::vector<std::vector<SheetCell>> sheet;
    std::vector<PlotColumn> sheetHistograms;
    if (!o.quiet) o.progress = terminalProgress("evaluating");
    if (Status s =
            predictFolds(variants, *dataset, *folds, *first, *mask, ptm, o, scratch, bankFiles, sheet, sheetHistograms);
        !s)
        return s;

    std::string context;
    if (!o.noGl)
        if (Status s = measureGl(variants, bankFiles, *dataset, o, context); !s) return s;
    if (views) context = "not measured: the GL figures draw a fixed camera's scene";
    Report r = report(variants, *dataset, o, *folds, mask->count(), context);
    r.json["contact_sheet"] = nlohmann::json::array();  // the held-out images on contact.png, top to bottom
    for (const std::vector<SheetCell>& row : sheet)     // a photograph's row (its error maps' row is under it)
        if (const std::size_t at = row.front().label.rfind(" (photo)"); at != std::string::npos)
            r.json["contact_sheet"].push_back(row.front().label.substr(0, at));
    if (!o.output.empty())
        if (Status s = writeReport(r, sheet, sheetHistograms, o); !s) return s;
    if (!o.quiet) std::cout << (o.json ? jsonText(r.json) : r.text);
    return success();
}

}  // namespace

void addEvalCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* app = root.add_subcommand(
        "eval",
        "Predict held-out photographs of a dataset in every mode and compare: histograms, pixels, memory, time");
    app->add_option("DATASET", o->dataset,
                    "a dataset (see btflut hist --help); with several views (a BTF, CUReT): held-out (light, view) "
                    "pairs, modes lut, nearest, brdf and flat (rectified views: and neuralN, and lut with --predictor "
                    "neuralN or auto)")
        ->required();
    app->add_option(
           "--holdout", o->holdout,
           "every:K (every K-th image, a light-view pair; one fold), loo (each image in turn), or a file naming one "
           "image per line: its name, or its light and view as THETA_I,PHI_I,THETA_R,PHI_R in degrees")
        ->capture_default_str();
    app->add_option(
           "--modes", o->modes,
           "comma-separated: lut, brdf, ptm, nearest, flat, and the RTI bases unmatched: hsh (hsh2, hsh3), rbf "
           "and bln (9 planes; rbfN, blnN: N planes; rbfNc, blnNc: N bytes of packed 8- and 4-bit planes), the "
           "learned kind (neural: 9 codes; neuralN) and the published NeuralRTI (neuralrti), its baseline")
        ->capture_default_str();
    app->add_option("--references", o->references, "lut: references per bank, a list (e.g. 1,4,6)")
        ->capture_default_str();
    app->add_option("--regions", o->regions, "lut: regions per bank, a list")->capture_default_str();
    app->add_option("--colour", o->colours, "lut: grey, rgb, lrgb, a list")->capture_default_str();
    app->add_option("--predictor", o->predictors,
                    "lut: auto (what bake makes without options, from each fold's training images), references (the "
                    "--references blended), or a light model relit, then matched: ptm, hsh2, hsh3, rbfN, blnN, rbfNc, "
                    "blnNc, neuralN (learned); a list")
        ->capture_default_str();
    app->add_option("--match", o->matches,
                    "lut with a predictor (and lut auto): each match strength of a list, 0 (the prediction as it is) "
                    "to 1 (the target's histogram), e.g. 0,0.5,1; default: bake's (auto: validated)");
    app->add_option("--budget", o->budgets,
                    "lut auto: each budget of a list, in bytes per texel the predictor may store (e.g. 3,6,9; "
                    "default: bake's); and a training time for the learned kinds, neural, neuralrti and lut auto's "
                    "candidates (e.g. 9,300s)");
    app->add_flag("--blended-luts", o->blendedLuts,
                  "also the alternative to blend-then-match: each reference matched alone, the results blended");
    app->add_option("--fill", o->fills,
                    "lut: clamp, model (bake --fill model, the model fitted to the training images), or both: "
                    "clamp,model")
        ->capture_default_str();
    app->add_option(
           "--target", o->targets,
           "lut with a predictor: measured (each light's target from the measured distributions, between the "
           "lights as bake's validation chooses: their blend, or the blend corrected by a smooth fit over the light), "
           "blend (the measured distributions blended alone), corrections (each node's LUT from the prediction to "
           "its measurement, blended at the light), or several: measured,blend")
        ->capture_default_str();
    app->add_option("--mask", o->mask, "sample mask instead of the dataset's own");
    app->add_option("--grid", o->grids, "banks' grid sizes, a list (e.g. 17,33,65)")->capture_default_str();
    app->add_option(
           "--luts", o->lutSources,
           "lut: exact (each light's LUT made at the light), grid (read bilinearly from the bank's grid, as an "
           "engine reads the export: for a bank with a predictor, the match LUTs baked over the grid), or "
           "both: exact,grid")
        ->capture_default_str();
    app->add_option(
           "--domain", o->domains,
           "the banks' domain: auto (bake's choice), layers (a LUT grid per view, blended between views), isotropic "
           "(light and view as one point of (theta_i, theta_r, phi_i - phi_r)), or a list: layers,isotropic; nearest "
           "measures there too")
        ->capture_default_str();
    app->add_option("--frames", o->frames, "GL frames per mode and round")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app->add_option("--backend", o->backend, "GL: auto, osmesa or egl")->capture_default_str();
    app->add_flag("--no-gl", o->noGl, "skip the GL figures (frame time, GPU bytes, GPU against CPU)");
    app->add_option("--contact", o->sheetLights, "held-out lights on the contact sheet")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    app->add_flag("--json", o->json, "print JSON instead of the table");
    app->add_option(
        "-o,--output", o->output,
        "folder for eval.txt, eval.json, rows.csv, contact.png, histograms.png, tradeoff.png and error_theta.png");
    addQuietFlag(*app, o->quiet, "print nothing (the figures go to -o DIR's files only)");
    commands.push_back({app, [o] { return runEval(*o); }});
}

}  // namespace btflut::cli
