// btflut bake: a LUT bank from a dataset.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/command.h"
#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bake/target_choice.h"
#include "core/bank/bank_file.h"
#include "core/inverse/fit.h"
#include "core/inverse/model_fill.h"
#include "core/io/json_text.h"
#include "core/predict/reference_blend.h"

namespace btflut::cli {

namespace {

struct BakeCommandOptions {
    std::string dataset;
    std::string output;
    std::string reference;
    std::string model;
    std::string mask;
    std::string referenceLight = "0,0";
    std::string colour = "grey";
    std::string domain = "auto";
    int grid = 17;
    int entries = 0;
    int references = 1;
    int regions = 1;
    int quantiles = 1024;
    std::string labels;
    std::string predictor = "auto";
    float match = -1;    ///< unset: 1, or validated with auto
    std::string budget;  // bytes 9 unless given
    std::string fill = "clamp";
    std::string params;
    std::string fitBrdf = "lambert";
    int threads = 0;
    bool noReference = false;
    bool ptm = false;
    bool quiet = false;
    bool json = false;  // the summary as JSON (no progress bar)
};

// A bank from the rough-surface model and one reference image.
Status runModelBake(const BakeCommandOptions& o) {
    if (!o.dataset.empty()) return Error{"give either a DATASET or --model, not both"};
    if (o.reference.empty()) return Error{"--model needs --reference IMAGE (the material's reference image)"};
    if (o.colour != "grey") return Error{"--model makes grey LUTs; --colour rgb needs measured images"};
    Result<ModelBankParams> params = loadModelParams(o.model);
    if (!params) return Error{params.error()};
    Result<Direction> light = parseDirection(o.referenceLight, "--reference-light");
    if (!light) return Error{light.error()};
    Result<Image> reference = loadImage(o.reference);
    if (!reference) return Error{reference.error()};
    Mask mask = fullMask(reference->width, reference->height);
    if (!o.mask.empty()) {
        Result<Mask> loaded = loadMask(o.mask, reference->width, reference->height);
        if (!loaded) return Error{loaded.error()};
        mask = std::move(*loaded);
    }
    ModelReference about{std::filesystem::path(o.reference).stem().string(), *light, o.grid, o.entries};
    Result<LutBank> bank = bakeModelBank(*params, *reference, mask, about);
    if (!bank) return Error{bank.error()};
    if (Status s = saveBank(*bank, o.output, {.embedReference = !o.noReference}); !s) return s;
    if (!o.quiet)
        std::cout << "wrote " << o.output << ": model r " << params->model.roughness << ", "
                  << bank->layers.front().nodes.size() << " model directions, reference " << o.reference << ", "
                  << std::filesystem::file_size(o.output) << " bytes\n";
    return success();
}

// Decodes a dataset's images for the bake and keeps each one's 64-bin masked grey histogram
// (what --fill model fits when no parameters are given): every image decoded once.
struct HistogramsWhileBaking {
    const Dataset& dataset;
    std::vector<std::vector<HistogramRow>> rows = std::vector<std::vector<HistogramRow>>(dataset.images.size());
    std::mutex maskLock;
    std::optional<Result<Mask>> mask;  ///< the dataset's, at the first image's size

    Result<const Image*> operator()(std::size_t i, Image& storage) {
        Result<Image> image = loadImage(dataset.images[i].path);
        if (!image) return Error{image.error()};
        storage = std::move(*image);
        const Mask* sample = nullptr;
        {
            std::lock_guard<std::mutex> lock(maskLock);
            if (!mask) mask = loadDatasetMask(dataset, storage.width, storage.height);
            if (*mask && (*mask)->width == storage.width && (*mask)->height == storage.height) sample = &**mask;
        }
        if (sample)  // else the bake refuses the image's size itself
            rows[i] = imageHistograms(storage, *sample, dataset.images[i].name, dataset.images[i].light,
                                      dataset.images[i].view, kFillHistogramBins, false);
        return &storage;
    }
    /// Every image's row, or nothing if some image was not seen.
    std::optional<std::vector<HistogramRow>> all() const {
        std::vector<HistogramRow> out;
        for (const std::vector<HistogramRow>& r : rows) {
            if (r.size() != 1) return std::nullopt;
            out.push_back(r.front());
        }
        return out;
    }
};

// --fill model: the fitted model's LUTs where the measured lights do not reach; fits the
// dataset's histograms first when no parameters file is given.
Status fillFromFittedModel(const BakeCommandOptions& o, const Dataset& dataset, LutBank& bank,
                           const std::vector<HistogramRow>* histograms) {
    std::optional<ModelBankParams> params;
    if (!o.params.empty()) {
        Result<ModelBankParams> parsed = loadModelParams(o.params);
        if (!parsed) return Error{parsed.error()};
        params = *parsed;
    }
    Result<FitBrdf> brdf = parseFitBrdf(o.fitBrdf);
    if (!brdf) return Error{"--fit-" + brdf.error()};
    Result<ModelFillReport> report = fillFromDataset(bank, dataset, params ? &*params : nullptr, *brdf, histograms);
    if (!report) return Error{report.error()};
    if (o.quiet) return success();
    if (report->fit)
        std::cout << "fitted " << fitBrdfName(*brdf) << ": r " << report->fit->model.roughness << ", gain "
                  << report->fit->model.gain << ", residual " << report->fit->rms << "\n";
    std::cout << "filled " << report->nodes << " directions from the model\n";
    return success();
}

// What `bank` predicts with and how its targets are estimated between the lights, for the
// summary line.
std::string predictorSummary(const LutBank& bank) {
    if (!bank.makesLuts())
        return bank.domain == BankDomain::Layers
                   ? ", targets between the measured lights: " + targetChoiceSummary(bank)
                   : ", targets between the measured light and view pairs: " + targetChoiceSummary(bank);
    const LutBank::Prediction& b = bank.prediction;
    // The name `--predictor` takes (bln9c, not the planes it unpacks to), as info prints it.
    const ReferenceBlend* references = bank.predictorAs<ReferenceBlend>();
    std::string s = references ? ", " + std::to_string(references->references().size()) + " reference(s)"
                               : ", " + bank.predictorName();
    char match[32];
    std::snprintf(match, sizeof match, "%.2f", static_cast<double>(b.match));
    // At a measured light every bank is matched fully (Relighter::matchAt).
    return s +
           (b.match == 1   ? " matched"
            : b.match == 0 ? " matched at the measured lights, unmatched between"
                           : std::string(" matched at the measured lights, ") + match + " between") +
           ", " + std::to_string(b.regions) + " region(s)" +
           (b.target == LutBank::Prediction::Target::Measured
                ? ", targets between the measured lights: " + targetChoiceSummary(bank)
                : std::string());
}

// Images at the light and view direction of an earlier one: bake averages their LUTs into that
// node (setNodes), so a bank has fewer measured nodes than images. "rock.2 at rock.1's".
std::vector<std::string> imagesSharingANode(const Dataset& dataset) {
    std::vector<std::string> shared;
    const auto& images = dataset.images;
    for (std::size_t i = 0; i < images.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (angleBetween(images[i].light, images[j].light) < kSameDirection &&
                angleBetween(images[i].view, images[j].view) < kSameDirection) {
                shared.push_back(images[i].name + " at " + images[j].name + "'s");
                break;
            }
    return shared;
}

// --budget: bytes per texel, a training time and/or a decoding bound in multiply-adds per texel
// ("9", "90s", "2m", "1500mac", "9,90s,1500mac").
struct Budget {
    std::optional<int> bytes;
    double seconds = 0;
    std::optional<std::size_t> multiplyAdds;
};
Result<Budget> parseBudget(const std::string& text) {
    Budget b;
    std::stringstream in(text);
    const Error bad{"--budget '" + text +
                    "': expected bytes per texel (1 to 64), a training time (90s, 2m), multiply-adds per texel "
                    "(1500mac), or several of them (9,90s,1500mac)"};
    for (std::string part; std::getline(in, part, ',');) {
        const bool macs = part.size() > 3 && part.compare(part.size() - 3, 3, "mac") == 0;
        const bool time = !macs && !part.empty() && (part.back() == 's' || part.back() == 'm');
        const std::string number = macs   ? part.substr(0, part.size() - 3)
                                   : time ? part.substr(0, part.size() - 1)
                                          : part;
        char* end = nullptr;
        const double value = std::strtod(number.c_str(), &end);
        if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value) || value <= 0) return bad;
        if (macs) {
            if (b.multiplyAdds || value != std::floor(value) || value > 1e7) return bad;
            b.multiplyAdds = static_cast<std::size_t>(value);
        } else if (time) {
            if (b.seconds > 0) return bad;
            b.seconds = part.back() == 'm' ? 60 * value : value;
            if (Status s = checkTrainingTime(b.seconds, text); !s) return Error{s.error()};
        } else {
            if (b.bytes || value != std::floor(value) || value > 64) return bad;
            b.bytes = static_cast<int>(value);
        }
    }
    return b;
}

// What a bake wrote: JSON (--json) or a line (not --quiet).
void reportBake(const BakeCommandOptions& o, const Dataset& dataset, const LutBank& bank) {
    std::size_t nodes = 0;
    for (const ViewLayer& l : bank.layers)
        for (const LightNode& n : l.nodes) nodes += !n.modelled;
    if (o.json) {
        nlohmann::json j{{"output", o.output},
                         {"images", dataset.images.size()},
                         {"view_layers", bank.layers.size()},
                         {"measured_nodes", nodes},
                         {"grid_size", bank.gridSize},
                         {"entries", bank.entries},
                         {"domain", domainName(bank.domain)},
                         {"colour", colourName(bank.colour)},
                         {"reference", bank.referenceName},
                         {"ptm", !bank.ptm.empty()},
                         {"chosen_by_validation", !bank.selection.empty()},
                         {"bytes", std::filesystem::file_size(o.output)},
                         {"images_sharing_a_node", imagesSharingANode(dataset)}};
        if (bank.makesLuts()) {
            j["predictor"] = bank.predictorName();
            j["bytes_per_texel"] = bank.predictorBytesPerTexel();
            j["match"] = bank.prediction.match;  // away from the measured lights; at them 1 (Relighter::matchAt)
            j["regions"] = bank.prediction.regions;
        }
        std::cout << jsonText(j);
    }
    if (!o.quiet) {
        std::string merged;  // why there are fewer nodes than images
        if (nodes < dataset.images.size())
            for (const std::string& pair : imagesSharingANode(dataset))
                merged += (merged.empty() ? " (averaged into one node, a light direction twice: " : "; ") + pair;
        if (!merged.empty()) merged += ")";
        std::cout << "wrote " << o.output << ": " << dataset.images.size() << " images, " << bank.layers.size()
                  << " view layer(s), " << nodes << " measured nodes" << merged << ", " << bank.gridSize << "x"
                  << bank.gridSize << " grid, " << bank.entries << " entries, domain " << domainName(bank.domain)
                  << ", colour " << colourName(bank.colour) << predictorSummary(bank)
                  << (bank.selection.empty() ? "" : " (chosen by validation; btflut info)") << ", reference "
                  << bank.referenceName << (bank.ptm.empty() ? "" : ", PTM") << ", "
                  << std::filesystem::file_size(o.output) << " bytes\n";
    }
}

Status runBake(const BakeCommandOptions& given, const CLI::App& app) {
    BakeCommandOptions o = given;
    // The references' options without --predictor mean the references, as before auto.
    const bool referencesAsked = app.count("--references") > 0 || o.colour != "grey" || !o.labels.empty();
    if (app.count("--predictor") == 0 && referencesAsked) o.predictor = "references";
    Result<Budget> budget = parseBudget(o.budget);
    if (!budget) return Error{budget.error()};
    if (budget->bytes && o.predictor != "auto") return Error{"--budget in bytes goes with --predictor auto"};
    if (budget->multiplyAdds && o.predictor != "auto")
        return Error{"--budget in multiply-adds bounds the candidates of --predictor auto"};
    if (budget->seconds > 0 && o.predictor != "auto" && !predictorTrains(o.predictor))
        return Error{"--budget in time bounds a learned model's training: --predictor auto or neuralN"};
    if (Status s = requireExtension(o.output, {"btflut"}, "output"); !s) return s;
    // A view layer's grid alone must fit a chunk of the file (4 GiB): refused before any work.
    const std::uint64_t gridBytes =
        static_cast<std::uint64_t>(o.grid) * o.grid * (o.entries ? o.entries : 1024) * (o.colour == "rgb" ? 3 : 1) * 2;
    if (gridBytes > 0xFFFFFFFFu)
        return Error{"--grid " + std::to_string(o.grid) + " with --entries " + std::to_string(o.entries) +
                     " makes a grid of " + std::to_string(gridBytes) +
                     " bytes per view, over the .btflut format's 4 GiB chunk limit"};
    if (o.fill != "model" && (!o.params.empty() || o.fitBrdf != "lambert"))
        return Error{"--params and --fit-brdf go with --fill model"};
    // --fill model's inputs checked before any work (fillFromFittedModel reads them after the bake).
    if (o.fill == "model") {
        if (Result<FitBrdf> brdf = parseFitBrdf(o.fitBrdf); !brdf) return Error{"--fit-" + brdf.error()};
        if (!o.params.empty())
            if (Result<ModelBankParams> parsed = loadModelParams(o.params); !parsed) return Error{parsed.error()};
        if (o.regions > 1) return Error{"--fill model: the model describes the whole sample, not each of --regions"};
    }
    if (!o.model.empty()) {
        if (o.fill == "model") return Error{"--fill model fills a measured bank; a --model bake is all model already"};
        return runModelBake(o);
    }
    if (o.dataset.empty()) return Error{"give a DATASET to bake, or --model PARAMS.json with --reference IMAGE"};
    Result<Dataset> dataset = openDatasetWithMask(o.dataset, o.mask);
    if (!dataset) return Error{dataset.error()};
    BakeOptions options;
    options.referenceName = o.reference;
    options.gridSize = o.grid;
    options.entries = o.entries;
    options.threads = o.threads;
    options.ptm = o.ptm;
    options.colour = o.colour == "rgb" ? ColourMode::Rgb : o.colour == "lrgb" ? ColourMode::Lrgb : ColourMode::Grey;
    if (o.domain != "auto") options.domain = *parseDomain(o.domain);
    options.references = o.references;
    if (o.predictor != "auto" && o.predictor != "references") {
        std::optional<Status> model = setModelNamed(options, o.predictor);
        if (!model)
            return Error{"--predictor '" + o.predictor +
                         "': expected auto, references, ptm, hsh, hsh2, hsh3, rbfN, blnN, neuralN or neuralNwW"};
        if (!*model) return Error{"--predictor " + model->error()};
    }
    if (o.match >= 0) options.match = o.match;
    options.regions = o.regions;
    options.quantiles = o.quantiles;
    options.labelsPath = o.labels;
    if (!o.labels.empty() && o.regions > 1) return Error{"give --regions or --labels, not both"};
    if (o.noReference && (options.predicts() || o.predictor == "auto"))
        return Error{
            "--no-reference: a bank that predicts (the default --predictor auto, references, a model) keeps "
            "what it predicts from; give --references 1 for the paper's bank"};
    if (o.json) o.quiet = true;  // stdout holds the JSON only
    if (!o.quiet) options.progress = terminalProgress(o.predictor == "auto" ? "validating" : "baking");
    // Training takes most of such a bake: its own bar, in thousandths.
    std::function<void(double)> training;
    if (!o.quiet && options.trains())
        if (auto bar = terminalProgress("training " + o.predictor))
            training = [bar](double done) mutable { bar(static_cast<std::size_t>(done * 1000), 1000); };
    options.setTraining(budget->seconds, std::move(training));
    HistogramsWhileBaking collector{*dataset};
    const bool fitting = o.fill == "model" && o.params.empty();
    const ImageProvider provider = fitting ? ImageProvider(std::ref(collector)) : ImageProvider();
    Result<LutBank> bank = Error{""};
    if (o.predictor == "auto") {
        AutoBakeOptions automatic{.base = options,
                                  .budget = budget->bytes.value_or(9),
                                  .decodeBudget = budget->multiplyAdds.value_or(kDefaultDecodeBudget),
                                  .seconds = budget->seconds > 0 ? budget->seconds : 3 * kDefaultTrainingSeconds};
        if (o.match >= 0) automatic.match = o.match;
        automatic.chooseQuantiles = app.count("--quantiles") == 0;
        if (!o.quiet && ::isatty(STDERR_FILENO))  // progress for people; errors stay one line
            automatic.log = [](const std::string& line) { std::cerr << "\rauto: " << line << "\x1b[K\n"; };
        if (!o.quiet)  // the chosen learned model's training: its own bar, in thousandths
            if (auto bar = terminalProgress("training the chosen model"))
                automatic.training = [bar](double done) mutable { bar(static_cast<std::size_t>(done * 1000), 1000); };
        bank = bakeAuto(*dataset, automatic, provider);
    } else {
        bank = bakeBank(*dataset, options, provider);
    }
    if (!bank) return Error{bank.error()};
    if (o.fill == "model") {
        const std::optional<std::vector<HistogramRow>> histograms = collector.all();
        if (Status s = fillFromFittedModel(o, *dataset, *bank, histograms ? &*histograms : nullptr); !s) return s;
    }
    if (Status s = saveBank(*bank, o.output, {.embedReference = !o.noReference}); !s) return s;
    reportBake(o, *dataset, *bank);
    return success();
}

}  // namespace

void addBakeCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<BakeCommandOptions>();
    CLI::App* app = root.add_subcommand("bake", "Bake a LUT bank (.btflut) from a dataset");
    app->add_option("DATASET", o->dataset, "dataset folder or file (see btflut hist --help)");
    app->add_option("-o,--output", o->output, "the bank, M.btflut")->required();
    app->add_option("--reference", o->reference,
                    "with a DATASET: name of the reference image (default: nearest to frontal view, then "
                    "light, among the images whose most common grey level holds at most a quarter of the "
                    "sample, as a LUT cannot spread such a tie; else the least tied); with --model: the "
                    "reference image file");
    app->add_option("--model", o->model,
                    "PARAMS.json: bake from the rough-surface model instead (docs/model-params.md)");
    app->add_option("--mask", o->mask,
                    "sample mask (non-zero = sample): with a DATASET instead of its own (an .lp capture's own is "
                    "the mask.png beside it); with --model, of the reference image");
    app->add_option("--reference-light", o->referenceLight,
                    "with --model: THETA,PHI of the light the reference image was taken under")
        ->capture_default_str();
    app->add_option("--grid", o->grid, "grid nodes per side over the equal-area light disk")
        ->check(CLI::Range(2, 257))
        ->capture_default_str();
    app->add_option("--entries", o->entries, "LUT entries (default 256, or 1024 for a 16-bit reference)")
        ->check(CLI::Range(2, 65536));
    app->add_option("--colour", o->colour,
                    "grey: one LUT on the grey value, the references' chroma kept; rgb: one LUT per channel; lrgb: "
                    "grey references and one RGB albedo (the PTM's layout: K + 3 bytes per texel)")
        ->check(CLI::IsMember({"grey", "rgb", "lrgb"}))
        ->capture_default_str();
    app->add_option("--references", o->references,
                    "K reference images spread over the measured lights (a fixed camera): at a light the references "
                    "around it are blended per texel and one LUT maps the blend onto the light's histogram, so "
                    "shadows and highlights move while the histogram stays the measured one. They are held in memory "
                    "while baking; 1 is the paper's bank. Given without --predictor (as --colour rgb|lrgb or "
                    "--labels are), it bakes the references' bank instead of --predictor auto")
        ->check(CLI::Range(1, 255))
        ->capture_default_str();
    app->add_option("--regions", o->regions,
                    "N regions segmented from how each pixel responds to the lights, each with its own histograms and "
                    "LUTs (a relief beside a flat background, paint beside gold leaf); the responses to up to 32 "
                    "lights are held in memory (32 bytes per pixel)")
        ->check(CLI::Range(1, 255))
        ->capture_default_str();
    app->add_option("--labels", o->labels, "instead of --regions: a label image, each grey value one region");
    app->add_option("--quantiles", o->quantiles,
                    "with --references, --regions or --predictor: samples of each target's quantile function (the "
                    "bank keeps them instead of LUTs; 4 bytes each per light and region). auto on a set of views, "
                    "without it: the fewest of 64 to 512 that validation finds to cost nothing, else 1024")
        ->check(CLI::Range(2, 65536))
        ->capture_default_str();
    app->add_option(
           "--predictor", o->predictor,
           "what places shadows and highlights before each light's LUT matches the histogram "
           "(docs/predictors.md): auto (the default without --references: validation on the dataset's own "
           "lights picks the predictor and how strongly to match, within --budget), references (the "
           "--references blended; --references 1 is the paper's bank), or a light model fitted to every "
           "image: ptm, hsh2 or hsh3 (hemispherical harmonics), rbfN or blnN (N principal components of "
           "the images, interpolated over the lights by radial basis functions or bilinearly; rbf, bln: 9), or a "
           "learned model trained on them: neuralN (N codes per texel and a small decoder network; neural: "
           "9; neuralNwW: its two hidden layers W wide, 24 otherwise). Several views: a learned model of the light and "
           "the view on rectified sets (auto validates it "
           "against the paper's bank), else the paper's bank")
        ->capture_default_str();
    app->add_option("--match", o->match,
                    "how far each light's LUT moves the prediction's distribution to the measured one: 1 fully, 0 not "
                    "at all (the prediction as it is), between: the two blended (default: 1, or validated with auto)")
        ->check(CLI::Range(0.0, 1.0));
    app->add_option(
        "--budget", o->budget,
        "BYTES, TIME, DECODE or several, comma-separated: bytes per texel the predictor may store (with "
        "--predictor auto; default 9); how long a learned model may train (auto: its candidate, a third "
        "for each fold and the bank; neuralN: the bank), as 90s or 2m: the steps this machine's trainer "
        "runs in that time on 2 cores (1.2e10 multiply-adds a second), so the bank is the same wherever it is baked; "
        "and the multiply-adds per texel a candidate's prediction may cost a GPU while the light moves, "
        "as 1500mac (auto; default 2000: neural9 decodes in 891)");
    app->add_option("--domain", o->domain,
                    "what lookups interpolate over: layers (each view's lights, then between views; any "
                    "material), isotropic (theta_i, theta_r, phi_i - phi_r; for isotropic materials measured "
                    "with light and view moving together, as CUReT), or auto: layers when every view's "
                    "lights span the light disk (or there is one view), isotropic otherwise")
        ->check(CLI::IsMember({"auto", "layers", "isotropic"}))
        ->capture_default_str();
    app->add_option("--fill", o->fill,
                    "light directions the measured lights do not enclose: clamp (to the nearest measured boundary) or "
                    "model (the fitted rough-surface model's LUTs there, marked as modelled in the bank; paper 6.5)")
        ->check(CLI::IsMember({"clamp", "model"}))
        ->capture_default_str();
    app->add_option(
        "--params", o->params,
        "with --fill model: the model's PARAMS.json (btflut fit writes it); without it the dataset is fitted "
        "first");
    app->add_option("--fit-brdf", o->fitBrdf, "with --fill model and no --params: the BRDF to fit (lambert, ts, mix)")
        ->capture_default_str();
    app->add_option("--threads", o->threads,
                    "worker threads (0 = all cores); images are decoded one per thread, so memory is "
                    "about the reference plus one decoded image (4 bytes per sample) per thread")
        ->check(CLI::Range(0, 1024));
    app->add_flag("--ptm", o->ptm,
                  "also fit a polynomial texture map (6 luminance coefficients + RGB albedo per texel) "
                  "to the images of the reference's view, the baseline of `btflut render --mode ptm`");
    app->add_flag("--no-reference", o->noReference,
                  "do not embed the reference image (relight then needs --reference-image)");
    addQuietFlag(*app, o->quiet, "no progress bar or summary");
    app->add_flag("--json", o->json,
                  "print the summary as JSON (output, images, nodes, grid, colour, predictor, match, bytes); no "
                  "progress bar");
    commands.push_back({app, [o, app] { return runBake(*o, *app); }});
}

}  // namespace btflut::cli
