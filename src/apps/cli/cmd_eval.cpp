// btflut eval: the held-out protocol as a command. Bakes from the training images, predicts
// every held-out image through the code users run (the Relighter behind `relight` and the GL
// renderer, the PTM, the nearest training image, ...) and compares each with the photograph.
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "cli/cli.h"
#include "core/bank/bake.h"
#include "core/bank/bank_file.h"
#include "core/eval/holdout.h"
#include "core/eval/metrics.h"
#include "core/histogram/plot.h"
#include "core/inverse/model_fill.h"
#include "core/io/json_text.h"
#include "core/predict/relighter.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/scene_renderer.h"

namespace btflut::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

struct EvalOptions {
    std::string dataset;
    std::string output;
    std::string holdout = "every:4";
    std::string modes = "lut,brdf,ptm,nearest";
    std::string references = "1";
    std::string regions = "1";
    std::string colours = "grey";
    std::string predictors = "references";
    std::string fills = "clamp";
    std::string mask;
    std::string backend = "auto";
    bool blendedLuts = false;
    bool json = false;
    bool noGl = false;
    int frames = 6;
    int grid = 17;
    int sheetLights = 4;
};

// One column of the report: a mode, and for lut the bank's setting.
struct Variant {
    std::string name;
    RenderMode mode = RenderMode::Lut;
    int references = 1, regions = 1;  // references 0: the PTM predictor
    ColourMode colour = ColourMode::Grey;
    bool filled = false;       // bake --fill model (fitted to the training images)
    bool blendedLuts = false;  // the alternative: per-reference LUTs blended
    bool base() const { return references == 1 && regions == 1 && colour == ColourMode::Grey && !filled; }
    using Setting = std::tuple<int, int, ColourMode, bool>;
    Setting setting() const { return {references, regions, colour, filled}; }

    std::vector<ImageErrors> errors;
    std::vector<std::string> images;
    std::vector<double> bakeSeconds, relightSeconds;
    double bytesPerTexel = 0;
    double gpuBytesPerTexel = std::nan(""), frameMs = std::nan(""), gpuMaxDiff = std::nan("");
};

Result<std::vector<int>> parseList(const std::string& text, const std::string& flag, int low, int high) {
    std::vector<int> values;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < low || v > high)
            return Error{"--" + flag + " '" + text + "': expected a comma-separated list of integers within " +
                         std::to_string(low) + ".." + std::to_string(high)};
        values.push_back(static_cast<int>(v));
    }
    if (values.empty()) return Error{"--" + flag + " is empty"};
    return values;
}

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> items;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) items.push_back(item);
    return items;
}

// The variants the options ask for, lut settings first.
Result<std::vector<Variant>> variantsOf(const EvalOptions& o) {
    Result<std::vector<int>> ks = parseList(o.references, "references", 1, 255), rs = parseList(o.regions, "regions", 1, 255);
    if (!ks) return Error{ks.error()};
    if (!rs) return Error{rs.error()};
    std::vector<Variant> variants;
    std::vector<std::string> modes = split(o.modes);
    if (modes.empty()) return Error{"--modes is empty"};
    for (const std::string& name : modes) {
        Result<RenderMode> mode = parseRenderMode(name);
        if (!mode) return Error{"--modes: " + mode.error()};
        if (*mode != RenderMode::Lut) {
            variants.push_back({name, *mode});
            continue;
        }
        for (const std::string& predictor : split(o.predictors)) {
            if (predictor == "references") continue;
            if (predictor != "ptm") return Error{"--predictor '" + predictor + "' is not references or ptm"};
            for (int r : *rs) variants.push_back({"lut ptm R" + std::to_string(r) + " grey", RenderMode::Lut, 0, r});
        }
        const std::vector<std::string> predictors = split(o.predictors);
        if (std::find(predictors.begin(), predictors.end(), "references") == predictors.end()) continue;
        for (const std::string& colourText : split(o.colours)) {
            if (colourText != "grey" && colourText != "rgb" && colourText != "lrgb")
                return Error{"--colour '" + colourText + "' is not grey, rgb or lrgb"};
            const ColourMode colour = colourText == "rgb" ? ColourMode::Rgb : colourText == "lrgb" ? ColourMode::Lrgb : ColourMode::Grey;
            for (int k : *ks)
                for (int r : *rs) {
                    Variant v{"lut K" + std::to_string(k) + " R" + std::to_string(r) + " " + colourText, RenderMode::Lut, k, r, colour};
                    variants.push_back(v);
                    if (o.blendedLuts && k > 1) {
                        v.name += " (LUTs blended)";
                        v.blendedLuts = true;
                        variants.push_back(v);
                    }
                }
        }
    }
    // Each lut bank clamped, filled from the model, or both.
    std::vector<std::string> fills = split(o.fills);
    if (fills.empty()) return Error{"--fill is empty"};
    for (const std::string& fill : fills)
        if (fill != "clamp" && fill != "model") return Error{"--fill '" + fill + "' is not clamp or model"};
    std::vector<Variant> all;
    for (const Variant& v : variants)
        for (const std::string& fill : fills) {
            if (v.mode != RenderMode::Lut && fill != fills.front()) continue;
            Variant f = v;
            f.filled = v.mode == RenderMode::Lut && fill == "model";
            if (v.mode == RenderMode::Lut && fills.size() > 1) f.name += fill == "model" ? " fill" : " clamp";
            all.push_back(f);
        }
    variants = std::move(all);
    // Lut variants first, then the baselines in the order asked.
    std::stable_partition(variants.begin(), variants.end(), [](const Variant& v) { return v.mode == RenderMode::Lut; });
    return variants;
}

BakeOptions bakeOptionsOf(const Variant& v, const EvalOptions& o, bool ptm) {
    BakeOptions b;
    b.gridSize = o.grid;
    b.references = std::max(v.references, 1);
    b.ptmPredictor = v.references == 0;
    b.regions = v.regions;
    b.colour = v.colour;
    b.ptm = ptm;
    return b;
}

// Data bytes per texel of what a mode draws from (no padding, no mipmaps).
double bytesPerTexel(const Variant& v, const LutBank& bank) {
    const double reference = bank.reference.channels * (bank.reference.bitDepth / 8.0);
    switch (v.mode) {
        case RenderMode::Lut:
            if (!bank.makesLuts()) return reference;
            if (bank.blend.predictor == LutBank::Blend::Predictor::Ptm) return 9 + (bank.blend.regions > 1 ? 1 : 0);
            return static_cast<double>(bank.blend.references.size()) * bank.blend.references.front().channels +
                   (bank.colour == ColourMode::Lrgb ? 3 : 0) + (bank.blend.regions > 1 ? 1 : 0);
        case RenderMode::Ptm: return 9;
        default: return reference;
    }
}

struct Report {
    std::string text;
    nlohmann::json json;
};

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
        std::snprintf(line, sizeof line, "%-30s %7.4f %7.4f %7.2f %6.3f %9.2f %9.2f %8.3f %6.2f ms %8.2f %8.1f\n", v.name.c_str(),
                      l1, emd, psnr, ssim, v.bytesPerTexel, v.gpuBytesPerTexel, bake, relight, v.frameMs, v.gpuMaxDiff);
        text += line;
        auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
        json["modes"].push_back({{"name", v.name}, {"mode", renderModeName(v.mode)}, {"references", v.references},
                                 {"regions", v.regions}, {"colour", colourName(v.colour)}, {"luts_blended", v.blendedLuts}, {"fill", v.filled ? "model" : "clamp"},
                                 {"l1", number(l1)}, {"emd", number(emd)}, {"psnr", number(psnr)}, {"ssim", number(ssim)},
                                 {"bytes_per_texel", v.bytesPerTexel}, {"gpu_bytes_per_texel", number(v.gpuBytesPerTexel)},
                                 {"bake_seconds", number(bake)}, {"relight_ms", number(relight)},
                                 {"frame_ms", number(v.frameMs)}, {"gpu_max_diff_255", number(v.gpuMaxDiff)}});
        for (std::size_t i = 0; i < v.errors.size(); ++i)
            json["rows"].push_back({{"image", v.images[i]}, {"mode", v.name}, {"l1", v.errors[i].l1}, {"emd", v.errors[i].emd},
                                    {"psnr", v.errors[i].psnr}, {"ssim", v.errors[i].ssim}});
    }
    text += "L1, EMD: masked 64-bin grey histograms against the photograph's; PSNR (dB, RGB) and SSIM (grey) over the mask;\n"
            "bytes/tx: data per texel a mode draws from (GPU B/tx: as allocated, padding and mipmaps included); bake s per\n"
            "bank; relight: CPU, one light change (LUTs and image); frame ms: GL, 4 quads at 1024x1024, the light moving;\n"
            "GPU-CPU: the largest difference of render --native from relight, in 1/255.\n";
    if (!context.empty()) text += "GL: " + context + "\n";
    return {text, json};
}

// GL figures per variant: frame times (interleaved rounds, the light moving every frame),
// texture bytes per texel, and for lut the largest difference of the native renderer from
// the CPU relighting.
Status measureGl(std::vector<Variant>& variants, const std::map<std::string, std::string>& bankFiles, const Dataset& dataset,
                 const EvalOptions& o, std::string& context) {
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> gl = createHeadlessContext(*backend);
    if (!gl) return Error{gl.error()};
    context = (*gl)->description();
    std::vector<std::unique_ptr<SceneRenderer>> renderers;
    for (Variant& v : variants) {
        Result<std::unique_ptr<SceneRenderer>> r =
            SceneRenderer::create(benchScene(bankFiles.at(v.name), 1024, 1024, dataset.source));
        if (!r) return Error{r.error()};
        renderers.push_back(std::move(*r));
    }
    std::vector<std::vector<double>> times(variants.size());
    for (int round = 0; round < 3; ++round)
        for (std::size_t i = 0; i < variants.size(); ++i)
            for (int f = 0; f < o.frames; ++f) {
                const auto start = Clock::now();
                if (Status s = renderers[i]->draw(benchLights()[static_cast<std::size_t>(f % 2)], variants[i].mode); !s) return s;
                renderers[i]->finish();
                if (round > 0 || f > 0) times[i].push_back(seconds(start) * 1e3);  // the first frame uploads
            }
    for (std::size_t i = 0; i < variants.size(); ++i) {
        Variant& v = variants[i];
        v.frameMs = median(times[i]);
        const RenderStats& stats = renderers[i]->stats();
        const TextureBytes& b = stats.textureBytes;
        const LutBank* bank = renderers[i]->bank("m");
        const double texels = static_cast<double>(bank->reference.pixelCount());
        const double quads = static_cast<double>(std::max<std::size_t>(stats.quadsDrawn, 1));
        double bytes = 0;
        switch (v.mode) {
            case RenderMode::Lut:  // what it reads, and one relit texture (per light direction)
                bytes = static_cast<double>(bank->makesLuts() ? b.blend : b.reference) + static_cast<double>(b.luts) / quads +
                        static_cast<double>(b.relit) / static_cast<double>(std::max<std::size_t>(stats.relitTextures, 1));
                break;
            case RenderMode::Ptm: bytes = static_cast<double>(b.ptm); break;
            case RenderMode::Nearest: bytes = static_cast<double>(b.images) / static_cast<double>(std::max<std::size_t>(stats.imagesLoaded, 1)); break;
            default: bytes = static_cast<double>(b.reference); break;
        }
        v.gpuBytesPerTexel = bytes / texels;
        if (v.mode == RenderMode::Lut && !v.blendedLuts) {
            // The native renderer against the CPU relighting, at the first held-out light.
            const Direction light = dataset.images.front().light;
            Result<Image> native = renderNative(*bank, light, bank->referenceView, true);
            if (!native) return Error{native.error()};
            const Relighter relighter(*bank);
            const Image cpu = quantised(relighter.apply(relighter.frame(light, bank->referenceView), true), 8);
            const Image gpu = quantised(*native, 8);
            double worst = 0;
            for (std::size_t s = 0; s < cpu.samples.size(); ++s)
                worst = std::max(worst, std::abs(static_cast<double>(cpu.samples[s]) - gpu.samples[s]) * 255.0);
            v.gpuMaxDiff = worst;
        }
    }
    return success();
}

Status runEval(const EvalOptions& o) {
    if (!o.output.empty()) {
        std::error_code ec;
        if (fs::exists(o.output, ec) && !fs::is_directory(o.output, ec)) return Error{o.output + ": exists and is not a folder"};
    }
    Result<std::vector<Variant>> parsed = variantsOf(o);
    if (!parsed) return Error{parsed.error()};
    std::vector<Variant>& variants = *parsed;
    Result<Dataset> dataset = openDatasetWithMask(o.dataset, o.mask);
    if (!dataset) return Error{dataset.error()};
    if (!dataset->fixedView()) return Error{o.dataset + ": eval needs a fixed camera (one view); this dataset has several"};
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
    if (!::mkdtemp(pattern.data())) return Error{"cannot create a temporary folder (" + std::string(std::strerror(errno)) + ")"};
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
    const std::size_t sheetEvery = std::max<std::size_t>(1, dataset->images.size() / std::max(o.sheetLights, 1));
    for (std::size_t f = 0; f < folds->size(); ++f) {
        const Fold& fold = (*folds)[f];
        const Dataset train = subset(*dataset, fold.train);
        // Banks per setting; the base (one grey reference) also serves brdf and ptm.
        std::map<Variant::Setting, std::unique_ptr<LutBank>> banks;
        std::map<Variant::Setting, std::unique_ptr<Relighter>> relighters;
        auto bankFor = [&](Variant& v) -> Result<LutBank*> {
            const auto key = v.mode == RenderMode::Lut ? v.setting() : Variant::Setting{1, 1, ColourMode::Grey, false};
            if (!banks.count(key)) {
                Variant setting = v;
                std::tie(setting.references, setting.regions, setting.colour, setting.filled) = key;
                const auto start = Clock::now();
                Result<LutBank> bank = bakeBank(train, bakeOptionsOf(setting, o, ptm && setting.base()));
                if (!bank) return Error{bank.error()};
                if (setting.filled)  // fitted to the training images only
                    if (Result<ModelFillReport> fill = fillFromDataset(*bank, train, nullptr); !fill) return Error{fill.error()};
                const double took = seconds(start);
                banks[key] = std::make_unique<LutBank>(std::move(*bank));
                relighters[key] = std::make_unique<Relighter>(*banks[key]);
                for (Variant& other : variants)
                    if (other.mode == RenderMode::Lut && other.setting() == key)
                        other.bakeSeconds.push_back(took);
            }
            LutBank* bank = banks[key].get();
            if (f == 0 && !bankFiles.count(v.name)) {
                const std::string path = (scratch / (std::to_string(bankFiles.size()) + ".btflut")).string();
                if (Status s = saveBank(*bank, path); !s) return Error{s.error()};
                bankFiles[v.name] = path;
                v.bytesPerTexel = bytesPerTexel(v, *bank);
            }
            return bank;
        };
        for (Variant& v : variants)
            if (Result<LutBank*> b = bankFor(v); !b) return Error{b.error()};

        const LevelCounts referenceGrey = [&] {
            const LutBank& base = *banks.begin()->second;
            return countGreyLevels(base.reference, fullMask(base.reference.width, base.reference.height));
        }();
        std::map<std::size_t, Image> trainImages;  // nearest: decoded once per fold
        for (std::size_t t : fold.test) {
            const DatasetImage& info = dataset->images[t];
            Result<Image> photo = loadImage(info.path);
            if (!photo) return Error{photo.error()};
            if (Status s = requireSameSize(*photo, info.path, first->width, first->height, dataset->images.front().path); !s)
                return Error{s.error()};
            const bool onSheet = t % sheetEvery == 0 && sheet.size() < static_cast<std::size_t>(o.sheetLights);
            if (onSheet) sheet.push_back({{info.name + " (photo)", *photo}});
            for (Variant& v : variants) {
                Result<LutBank*> found = bankFor(v);
                if (!found) return Error{found.error()};
                const LutBank& bank = **found;
                Image predicted;
                if (v.mode == RenderMode::Lut) {
                    const Relighter& relighter = *relighters.at(v.setting());
                    const auto start = Clock::now();
                    predicted = v.blendedLuts ? relighter.applyBlendingLuts(info.light, info.view, true)
                                              : relighter.apply(relighter.frame(info.light, info.view), true);
                    v.relightSeconds.push_back(seconds(start));
                } else if (v.mode == RenderMode::Ptm) {
                    predicted = bank.ptm.render(info.light);
                } else if (v.mode == RenderMode::Nearest) {
                    std::size_t nearest = fold.train.front();
                    for (std::size_t i : fold.train)
                        if (angleBetween(dataset->images[i].light, info.light) < angleBetween(dataset->images[nearest].light, info.light))
                            nearest = i;
                    if (!trainImages.count(nearest)) {
                        Result<Image> image = loadImage(dataset->images[nearest].path);
                        if (!image) return Error{image.error()};
                        trainImages.emplace(nearest, std::move(*image));
                    }
                    predicted = trainImages.at(nearest);
                } else {
                    predicted = bank.reference;
                    if (v.mode == RenderMode::Brdf) {
                        const float scale = brdfScale(bank, referenceGrey, bank.lookup(info.light, info.view));
                        for (float& s : predicted.samples) s = std::min(1.f, s * scale);
                    }
                }
                v.errors.push_back(compareImages(predicted, *photo, *mask));
                v.images.push_back(info.name);
                if (onSheet) sheet.back().push_back({v.name, std::move(predicted)});
            }
        }
    }

    std::string context;
    if (!o.noGl)
        if (Status s = measureGl(variants, bankFiles, *dataset, o, context); !s) return s;
    const Report r = report(variants, *dataset, o, *folds, mask->count(), context);
    if (!o.output.empty()) {
        std::error_code ec;
        fs::create_directories(o.output, ec);
        if (ec) return Error{o.output + ": cannot create the folder (" + ec.message() + ")"};
        std::string csv = "image,mode,l1,emd,psnr,ssim\n";
        for (const nlohmann::json& row : r.json["rows"]) {
            char line[512];
            std::snprintf(line, sizeof line, "%s,%s,%.6f,%.6f,%.4f,%.5f\n", row["image"].get<std::string>().c_str(),
                          row["mode"].get<std::string>().c_str(), row["l1"].get<double>(), row["emd"].get<double>(),
                          row["psnr"].get<double>(), row["ssim"].get<double>());
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
    }
    std::cout << (o.json ? jsonText(r.json) : r.text);
    return success();
}

}  // namespace

void addEvalCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* app = root.add_subcommand(
        "eval", "Predict held-out photographs of a dataset in every mode and compare: histograms, pixels, memory, time");
    app->add_option("DATASET", o->dataset, "a dataset with a fixed camera (see btflut hist --help)")->required();
    app->add_option("--holdout", o->holdout,
                    "every:K (every K-th image; one fold), loo (each image in turn), or a file of image names")
        ->capture_default_str();
    app->add_option("--modes", o->modes, "comma-separated: lut, brdf, ptm, nearest, flat")->capture_default_str();
    app->add_option("--references", o->references, "lut: references per bank, a list (e.g. 1,4,6)")->capture_default_str();
    app->add_option("--regions", o->regions, "lut: regions per bank, a list")->capture_default_str();
    app->add_option("--colour", o->colours, "lut: grey, rgb, lrgb, a list")->capture_default_str();
    app->add_option("--predictor", o->predictors, "lut: references, ptm (the PTM relit, then matched), a list")
        ->capture_default_str();
    app->add_flag("--blended-luts", o->blendedLuts,
                  "also the alternative to blend-then-match: each reference matched alone, the results blended");
    app->add_option("--fill", o->fills,
                    "lut: clamp, model (bake --fill model, the model fitted to the training images), or both: "
                    "clamp,model")
        ->capture_default_str();
    app->add_option("--mask", o->mask, "sample mask instead of the dataset's own");
    app->add_option("--grid", o->grid, "banks' grid size")->check(CLI::Range(2, 257))->capture_default_str();
    app->add_option("--frames", o->frames, "GL frames per mode and round")->check(CLI::Range(1, 1000))->capture_default_str();
    app->add_option("--backend", o->backend, "GL: auto, osmesa or egl")->capture_default_str();
    app->add_flag("--no-gl", o->noGl, "skip the GL figures (frame time, GPU bytes, GPU against CPU)");
    app->add_option("--contact", o->sheetLights, "held-out lights on the contact sheet")->check(CLI::Range(1, 64))->capture_default_str();
    app->add_flag("--json", o->json, "print JSON instead of the table");
    app->add_option("-o,--output", o->output, "folder for eval.txt, eval.json, rows.csv and contact.png");
    commands.push_back({app, [o] { return runEval(*o); }});
}

}  // namespace btflut::cli
