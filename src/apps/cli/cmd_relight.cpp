// btflut relight: the CPU reference of the renderer — the reference image with the LUT
// for one light (and view) direction applied.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "core/relight/relighter.h"

namespace btflut::cli {

namespace {

struct RelightOptions {
    std::string bank;
    std::string light;
    std::string view;
    std::string output;
    std::string referenceImage;
    int depth = 8;
    bool noDither = false;
    bool grid = false;
    bool quiet = false;
    bool json = false;
};

// What was written and where the light fell: a line, or JSON (--json).
void report(const RelightOptions& o, const Image& out, const std::string& lut, Direction light,
            const RelightFrame* frame, float match) {
    if (o.json) {
        nlohmann::json j{{"output", o.output},
                         {"width", out.width},
                         {"height", out.height},
                         {"light", {{"theta", light.theta * 180 / M_PI}, {"phi", light.phi * 180 / M_PI}}},
                         {"lut", lut}};
        if (frame) {
            j["light_provenance"] = provenanceName(frame->lightProvenance);
            j["view_provenance"] = provenanceName(frame->viewProvenance);
        }
        if (match >= 0) j["match"] = match;  // the strength at this light (a bank with a predictor)
        std::cout << jsonText(j);
    } else if (!o.quiet) {
        std::cout << "wrote " << o.output << " (" << out.width << "x" << out.height << ", LUT " << lut << ")\n";
    }
}

// A light beyond the measured ones gets the nearest edge's LUT (clamped): for a narrow capture
// that can be far from the light asked for, so say so, why (past their highest theta, or in an
// azimuth gap of theirs), and what fills such lights instead.
void noteClampedLight(const LutBank& bank, const RelightFrame& frame, Direction light) {
    if (frame.lightProvenance != Provenance::Clamped) return;
    constexpr double kDegrees = 180 / M_PI;
    double reach = 0;
    std::vector<double> phis;  // the measured lights' azimuths, off the zenith
    const ViewLayer& layer = bank.layers.front();
    for (std::size_t n = 0; n < layer.measuredNodes; ++n) {
        const Direction l = layer.nodes[n].light;
        reach = std::max(reach, l.theta);
        if (l.theta > 1 / kDegrees) phis.push_back(std::fmod(l.phi * kDegrees + 360, 360));
    }
    std::string why;
    char text[200];
    if (light.theta > reach || phis.empty()) {
        std::snprintf(text, sizeof text, "its theta is past theirs (they reach theta %.1f)", reach * kDegrees);
        why = text;
    } else {
        // The azimuth gap the light falls in: the measured azimuths on either side of it.
        std::sort(phis.begin(), phis.end());
        const double phi = std::fmod(light.phi * kDegrees + 360, 360);
        auto above = std::upper_bound(phis.begin(), phis.end(), phi);
        const double after = above == phis.end() ? phis.front() : *above,
                     before = above == phis.begin() ? phis.back() : *(above - 1);
        std::snprintf(text, sizeof text,
                      "its theta is within theirs (up to %.1f), but no measured light lies between phi %.1f and "
                      "%.1f, where its phi is",
                      reach * kDegrees, before, after);
        why = text;
    }
    char line[600];
    std::snprintf(
        line, sizeof line,
        "btflut relight: note: the light (theta %.1f, phi %.1f) is outside the measured lights' hull: %s; its "
        "LUT is clamped to the nearest measured edge's, which can show wrong shadows and speckle far from it; "
        "`bake --fill model` fills such lights from the fitted rough-surface model\n",
        light.theta * kDegrees, light.phi * kDegrees, why.c_str());
    std::cerr << line;
}

Status runRelight(const RelightOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    Result<BankAtDirection> query = loadBankAt(o.bank, o.light, o.view);
    if (!query) return Error{query.error()};
    LutBank& bank = query->bank;
    if (!o.referenceImage.empty()) {
        if (bank.makesLuts()) return Error{o.bank + ": --reference-image: this bank blends its own references"};
        Result<Image> image = loadImage(o.referenceImage);
        if (!image) return Error{image.error()};
        // The LUTs map the reference's own codes: another size, channel count or bit depth
        // is another image.
        const Image& ref = bank.reference;
        if (image->width != ref.width || image->height != ref.height || image->channels != ref.channels ||
            image->bitDepth != ref.bitDepth)
            return Error{o.referenceImage + ": the bank's reference is " + std::to_string(ref.width) + "x" +
                         std::to_string(ref.height) + " with " + std::to_string(ref.channels) + " channel(s) at " +
                         std::to_string(ref.bitDepth) + " bits, this image is " + std::to_string(image->width) + "x" +
                         std::to_string(image->height) + " with " + std::to_string(image->channels) + " at " +
                         std::to_string(image->bitDepth)};
        bank.reference = std::move(*image);
    }
    if (bank.reference.samples.empty())
        return Error{o.bank + ": the bank has no reference image inside; give --reference-image"};
    if (o.grid && bank.makesLuts()) {  // the prediction, then the LUT read from the bank's match grid
        const Relighter relighter(bank);
        // A predictor of views: predicted at the view, matched by the nearest layer's grid.
        const RelightFrame frame =
            relighter.gridFrame(query->light, query->view, bank.nearestNode(query->light, query->view).layer);
        const Image out = relighter.apply(frame, !o.noDither);
        if (Status s = savePng(out, o.output, o.depth); !s) return s;
        report(o, out, "from the match grid", query->light, &frame, relighter.matchAt(query->light, query->view));
        return success();
    }
    if (o.grid) {  // what an engine reads from `export -o DIR/`
        const std::size_t layer = bank.nearestNode(query->light, query->view).layer;
        const Image out = applyLuts(bank.reference, bank.colour, bank.gridLookup(query->light, layer), bank.entries,
                                    o.noDither ? 0.f : bank.targetCode());
        if (Status s = savePng(out, o.output, o.depth); !s) return s;
        report(o, out, "from the grid", query->light, nullptr, -1);
        return success();
    }
    const Relighter relighter(bank);
    const RelightFrame frame = relighter.frame(query->light, query->view);
    if (!o.quiet && !o.json) noteClampedLight(bank, frame, query->light);
    Image out = relighter.apply(frame, !o.noDither);
    if (Status s = savePng(out, o.output, o.depth); !s) return s;
    report(o, out, provenanceName(frame.provenance), query->light, &frame,
           bank.makesLuts() ? relighter.matchAt(query->light, query->view) : -1);
    return success();
}

}  // namespace

void addRelightCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<RelightOptions>();
    CLI::App* app =
        root.add_subcommand("relight", "Apply the bank's LUT for a light (and view) direction to its reference image");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("--light", o->light, "light direction THETA,PHI in degrees")->required();
    app->add_option("--view", o->view, "view direction THETA,PHI in degrees (default: the reference image's view)");
    app->add_option("-o,--output", o->output, "out.png")->required();
    addLutImageOptions(*app, o->depth, o->noDither);
    app->add_option("--reference-image", o->referenceImage, "reference image, for a bank baked with --no-reference");
    app->add_flag(
        "--grid", o->grid,
        "the LUT as an engine reads it from the exported grid (bilinear between grid nodes, as "
        "shaders/btflut.glsl's one filtered fetch), not interpolated over the measured directions; for a bank "
        "with a predictor, the LUT baked over the grid (no counting of the prediction per light)");
    addQuietFlag(*app, o->quiet, "do not say what was written");
    app->add_flag("--json", o->json,
                  "print what was written and where the light fell as JSON: output, size, the light, the LUT's "
                  "source (measured, interpolated, modelled, clamped, or a grid), the light's and view's "
                  "provenance, the match strength there");
    commands.push_back({app, [o] { return runRelight(*o); }});
}

}  // namespace btflut::cli
