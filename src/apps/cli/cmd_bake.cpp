// btflut bake: a LUT bank from a dataset.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "core/bank_file.h"

namespace btflut::cli {

namespace {

struct BakeCommandOptions {
    std::string dataset;
    std::string output;
    std::string reference;
    std::string colour = "grey";
    int grid = 17;
    int entries = 0;
    int threads = 0;
    bool noReference = false;
    bool quiet = false;
};

Status runBake(const BakeCommandOptions& o) {
    if (Status s = requireExtension(o.output, {"btflut"}, "output"); !s) return s;
    Result<Dataset> dataset = openDataset(o.dataset);
    if (!dataset) return Error{dataset.error()};
    BakeOptions options;
    options.referenceName = o.reference;
    options.gridSize = o.grid;
    options.entries = o.entries;
    options.threads = o.threads;
    options.colour = o.colour == "rgb" ? ColourMode::Rgb : ColourMode::Grey;
    if (!o.quiet) options.progress = terminalProgress("baking");
    Result<LutBank> bank = bakeBank(*dataset, options);
    if (!bank) return Error{bank.error()};
    if (Status s = saveBank(*bank, o.output, {.embedReference = !o.noReference}); !s) return s;
    if (!o.quiet) {
        std::size_t nodes = 0;
        for (const ViewLayer& l : bank->layers) nodes += l.nodes.size();
        std::cout << "wrote " << o.output << ": " << dataset->images.size() << " images, "
                  << bank->layers.size() << " view layer(s), " << nodes << " measured nodes, "
                  << bank->gridSize << "x" << bank->gridSize << " grid, " << bank->entries
                  << " entries, reference " << bank->referenceName << ", "
                  << std::filesystem::file_size(o.output) << " bytes\n";
    }
    return success();
}

}  // namespace

void addBakeCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<BakeCommandOptions>();
    CLI::App* app = root.add_subcommand("bake", "Bake a LUT bank (.btflut) from a dataset");
    app->add_option("DATASET", o->dataset, "dataset folder or file (see btflut hist --help)")
        ->required();
    app->add_option("-o,--output", o->output, "the bank, M.btflut")->required();
    app->add_option("--reference", o->reference,
                    "name of the reference image (default: nearest to frontal light and view)");
    app->add_option("--grid", o->grid, "grid nodes per side over the equal-area light disk")
        ->check(CLI::Range(2, 257))
        ->capture_default_str();
    app->add_option("--entries", o->entries,
                    "LUT entries (default 256, or 1024 for a 16-bit reference)")
        ->check(CLI::Range(2, 65536));
    app->add_option("--colour", o->colour, "grey: one LUT on the grey value; rgb: one per channel")
        ->check(CLI::IsMember({"grey", "rgb"}))
        ->capture_default_str();
    app->add_option("--threads", o->threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    app->add_flag("--no-reference", o->noReference,
                  "do not embed the reference image (relight then needs --reference-image)");
    app->add_flag("-q,--quiet", o->quiet, "no progress bar or summary");
    commands.push_back({app, [o] { return runBake(*o); }});
}

}  // namespace btflut::cli
