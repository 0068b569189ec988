// btflut plot: histogram CSV files as a figure in the paper's layout.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/command.h"
#include "core/histogram/plot.h"

namespace btflut::cli {

namespace {

struct PlotOptions {
    bool quiet = false;
    std::vector<std::string> inputs;
    std::string output;
    bool overlay = false;
};

Status runPlot(const PlotOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    std::vector<PlotColumn> columns;
    for (const std::string& input : o.inputs) {
        Result<Bytes> text = readFile(input);
        if (!text) return Error{text.error()};
        Result<std::vector<HistogramRow>> rows = parseHistogramCsv(std::string(text->begin(), text->end()), input);
        if (!rows) return Error{rows.error()};
        if (rows->empty()) return Error{input + ": no histograms to plot"};
        columns.push_back({std::filesystem::path(input).stem().string(), std::move(*rows)});
    }
    Image figure =
        plotHistograms(columns, {.layout = o.overlay ? PlotStyle::Layout::Overlay : PlotStyle::Layout::Columns});
    if (Status s = savePng(figure, o.output); !s) return s;
    if (!o.quiet) std::cout << "wrote " << o.output << " (" << figure.width << "x" << figure.height << ")\n";
    return success();
}

}  // namespace

void addPlotCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<PlotOptions>();
    CLI::App* app =
        root.add_subcommand("plot",
                            "Histogram CSV files (as hist and simulate write them) as a figure: one panel per "
                            "position, one column per file");
    app->add_option("CSV", o->inputs, "one or more histogram CSV files")->required();
    app->add_option("-o,--output", o->output, "fig.png")->required();
    app->add_flag("--overlay", o->overlay,
                  "all files in one panel per position (the first as bars, the others as outlines, with a legend)");
    addQuietFlag(*app, o->quiet);
    commands.push_back({app, [o] { return runPlot(*o); }});
}

}  // namespace btflut::cli
