// btflut match: give one image the grey-level histogram of another (one LUT, as baked).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/bank/lut_bank.h"
#include "core/io/json_text.h"

namespace btflut::cli {

namespace {

struct MatchOptions {
    bool quiet = false;
    std::string source;
    std::string target;
    std::string output;
    std::string mask;
    std::string targetMask;
    int entries = 0;
    int depth = 8;
    bool noDither = false;
    bool json = false;
};

Status runMatch(const MatchOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    // The statistics of the masks' pixels; every pixel of the source is mapped.
    Result<SampleImage> source = loadSampleImage(o.source, o.mask);
    if (!source) return Error{source.error()};
    Result<SampleImage> target = loadSampleImage(o.target, o.targetMask);
    if (!target) return Error{target.error()};
    LevelCounts from = countGreyLevels(source->image, source->mask);
    LevelCounts to = countGreyLevels(target->image, target->mask);
    if (from.presentCodes() < 2)
        return Error{o.source + ": constant over its mask, so no LUT can give it another histogram"};
    // Enough entries to hold every code of a grey 8-bit source exactly.
    int entries = o.entries ? o.entries : (source->image.bitDepth == 16 ? 4096 : 256);
    Lut lut = matchLut(from, to, entries);
    const float targetCode = 1.f / static_cast<float>(to.counts.size() - 1);
    Image out = applyLuts(source->image, ColourMode::Grey, lut.values, entries, o.noDither ? 0.f : targetCode);
    if (Status s = savePng(out, o.output, o.depth); !s) return s;
    if (o.json)
        std::cout << jsonText({{"output", o.output},
                               {"width", out.width},
                               {"height", out.height},
                               {"source", o.source},
                               {"target", o.target},
                               {"entries", entries},
                               {"dithered", !o.noDither}});
    else if (!o.quiet)
        std::cout << "wrote " << o.output << "\n";
    return success();
}

}  // namespace

void addMatchCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<MatchOptions>();
    CLI::App* app = root.add_subcommand("match", "Give SOURCE the grey-level histogram of TARGET (histogram matching)");
    app->add_option("SOURCE", o->source, "image whose pixels are mapped")->required();
    app->add_option("TARGET", o->target, "image whose histogram is wanted")->required();
    app->add_option("-o,--output", o->output, "out.png")->required();
    app->add_option("--mask", o->mask,
                    "the source's sample pixels (non-zero): their histogram is matched, every pixel mapped");
    app->add_option("--target-mask", o->targetMask, "the target's sample pixels (non-zero): the histogram wanted");
    app->add_option("--entries", o->entries, "LUT entries (default 256, 4096 for 16-bit)")->check(CLI::Range(2, 65536));
    addLutImageOptions(*app, o->depth, o->noDither);
    addQuietFlag(*app, o->quiet);
    app->add_flag("--json", o->json, "print what was written as JSON (output, size, source, target, LUT entries)");
    commands.push_back({app, [o] { return runMatch(*o); }});
}

}  // namespace btflut::cli
