// btflut classify: which material of a library one image shows, under an unknown light (paper 6.3).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/inverse/classify.h"
#include "core/io/json_text.h"

namespace btflut::cli {

namespace {

struct ClassifyCommandOptions {
    std::string image;
    std::string library;
    std::string view = "0,0";
    std::string mask;
    std::string metric = "histogram";
    int top = 5;
    bool json = false;
};

// Every bank and model parameters file of a folder, by name.
Result<std::vector<MaterialHistograms>> loadLibrary(const std::string& folder) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        return Error{folder + ": not a folder (the library is a folder of .btflut banks and PARAMS.json models)"};
    std::vector<std::string> paths;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
        const std::string extension = fileExtension(entry.path().string());
        if (entry.is_regular_file(ec) && (extension == "btflut" || extension == "json"))
            paths.push_back(entry.path().string());
    }
    if (ec) return Error{folder + ": cannot list the folder (" + ec.message() + ")"};
    if (paths.empty()) return Error{folder + ": the library is empty (no .btflut banks or PARAMS.json models)"};
    std::sort(paths.begin(), paths.end());
    std::vector<MaterialHistograms> library;
    for (const std::string& path : paths) {
        Result<MaterialHistograms> material = loadMaterial(path);
        if (!material) return Error{material.error()};
        library.push_back(std::move(*material));
    }
    return library;
}

Status runClassify(const ClassifyCommandOptions& o) {
    Result<Direction> view = parseDirection(o.view, "--view");
    if (!view) return Error{view.error()};
    Result<std::vector<MaterialHistograms>> library = loadLibrary(o.library);
    if (!library) return Error{library.error()};
    Result<SampleImage> sample = loadSampleImage(o.image, o.mask);
    if (!sample) return Error{sample.error()};
    const std::vector<double> histogram = binHistogram(countGreyLevels(sample->image, sample->mask), 64);
    const Metric metric = o.metric == "mean" ? Metric::MeanBrightness : Metric::Histogram;
    const std::vector<MaterialMatch> ranked = classify(histogram, *library, *view, metric);
    const std::size_t shown = std::min<std::size_t>(ranked.size(), static_cast<std::size_t>(o.top));

    if (o.json) {
        nlohmann::json out{
            {"image", o.image}, {"library", o.library}, {"metric", o.metric}, {"matches", nlohmann::json::array()}};
        for (std::size_t k = 0; k < shown; ++k) {
            const MaterialHistograms& m = (*library)[ranked[k].material];
            out["matches"].push_back({{"material", m.name},
                                      {"path", m.path},
                                      {"score", ranked[k].score},
                                      {"light", directionJson(ranked[k].light)}});
        }
        std::cout << jsonText(out);
        return success();
    }
    std::cout << o.image << ": " << (o.metric == "mean" ? "mean brightness" : "histogram") << " against "
              << library->size() << " material(s), each at its best light:\n";
    for (std::size_t k = 0; k < shown; ++k) {
        const MaterialHistograms& m = (*library)[ranked[k].material];
        char line[256];
        std::snprintf(line, sizeof line, "  %zu. %-24s %s %.4f at light (%.1f, %.1f)\n", k + 1, m.name.c_str(),
                      o.metric == "mean" ? "|mean difference|" : "EMD", ranked[k].score, ranked[k].light.thetaDegrees(),
                      ranked[k].light.phiDegrees());
        std::cout << line;
    }
    return success();
}

}  // namespace

void addClassifyCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ClassifyCommandOptions>();
    CLI::App* app = root.add_subcommand(
        "classify",
        "Which material of a library one image shows, under an unknown light: top-k scores from histograms");
    app->add_option("IMAGE", o->image, "the image of the sample")->required();
    app->add_option("--library", o->library, "a folder of materials: banks (.btflut) and fitted models (PARAMS.json)")
        ->required();
    app->add_option("--view", o->view, "THETA,PHI: the camera in the sample's frame")->capture_default_str();
    app->add_option("--mask", o->mask, "the sample's pixels (non-zero) in the image; default every pixel");
    app->add_option("--metric", o->metric,
                    "histogram (earth mover's distance of the 64-bin histograms) or mean (mean brightness alone: the "
                    "baseline a BRDF gives)")
        ->check(CLI::IsMember({"histogram", "mean"}))
        ->capture_default_str();
    app->add_option("--top", o->top, "how many matches to print")->check(CLI::Range(1, 1000))->capture_default_str();
    app->add_flag("--json", o->json, "print JSON");
    commands.push_back({app, [o] { return runClassify(*o); }});
}

}  // namespace btflut::cli
