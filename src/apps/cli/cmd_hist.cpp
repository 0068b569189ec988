// btflut hist: the masked, normalised histogram of every image of a dataset.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/data/dataset.h"
#include "core/histogram/histogram.h"
#include "core/io/json_text.h"
#include "core/parallel.h"

namespace btflut::cli {

namespace {

struct HistOptions {
    bool quiet = false;
    bool json = false;
    std::string dataset;
    std::string output;
    int bins = 64;
    std::string channels = "grey";
    std::string mask;
};

// One image: its histogram (or three), with no directions (0, 0 for light and view).
Result<std::vector<HistogramRow>> imageHistograms(const HistOptions& o) {
    Result<SampleImage> sample = loadSampleImage(o.dataset, o.mask);
    if (!sample) return Error{sample.error()};
    const bool rgb = o.channels == "rgb";
    if (rgb && sample->image.channels != 3)
        return Error{o.dataset + ": --channels rgb needs a colour image, this one is grey"};
    return imageHistograms(sample->image, sample->mask, std::filesystem::path(o.dataset).stem().string(), {}, {},
                           o.bins, rgb);
}

Status runHist(const HistOptions& o) {
    if (Status s = requireExtension(o.output, {"csv", "json"}, "output"); !s) return s;
    Result<std::vector<HistogramRow>> rows = isImageExtension(fileExtension(o.dataset))
                                                 ? imageHistograms(o)
                                                 : datasetHistograms(o.dataset, o.mask, o.bins, o.channels == "rgb");
    if (!rows) return Error{rows.error()};
    if (Status s = saveHistograms(*rows, o.output); !s) return s;
    if (o.json)
        std::cout << jsonText(
            {{"output", o.output}, {"histograms", rows->size()}, {"bins", o.bins}, {"channels", o.channels}});
    else if (!o.quiet)
        std::cout << "wrote " << o.output << ": " << rows->size() << " histogram(s) of " << o.bins << " bins\n";
    return success();
}

}  // namespace

Result<std::vector<HistogramRow>> datasetHistograms(const std::string& path, const std::string& maskPath, int bins,
                                                    bool rgb) {
    Result<Dataset> dataset = openDatasetWithMask(path, maskPath);
    if (!dataset) return Error{dataset.error()};
    return histogramsOf(*dataset, bins, rgb);
}

void addHistCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<HistOptions>();
    CLI::App* app = root.add_subcommand(
        "hist", "Masked, normalised grey-level histogram of every image of a dataset, or of one image");
    app->add_option("DATASET", o->dataset,
                    "folder or file: btflut manifest (.json), RTI (.lp), photometric-stereo "
                    "folder (lights.txt) or Bonn UBO2003 folder; or one image (its directions written as 0)")
        ->required();
    app->add_option("-o,--output", o->output, "FILE.csv (name,theta_i,phi_i,theta_r,phi_r,b0..b{N-1}) or FILE.json")
        ->required();
    app->add_option("--bins", o->bins, "number of equal bins over [0, 1]")
        ->check(CLI::Range(2, 1 << 20))
        ->capture_default_str();
    app->add_option("--channels", o->channels,
                    "grey: mean of R, G, B; rgb: one row per channel, named NAME:R, NAME:G, NAME:B")
        ->check(CLI::IsMember({"grey", "rgb"}))
        ->capture_default_str();
    app->add_option("--mask", o->mask, "sample mask instead of the dataset's own (non-zero = sample)");
    addQuietFlag(*app, o->quiet);
    app->add_flag("--json", o->json, "print what was written as JSON (output, histograms, bins, channels)");
    commands.push_back({app, [o] { return runHist(*o); }});
}

}  // namespace btflut::cli
