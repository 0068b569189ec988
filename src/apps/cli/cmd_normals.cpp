// btflut normals: a capture's normal map and albedo by photometric stereo (docs/engines.md).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/inverse/photometric_stereo.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"

namespace btflut::cli {

namespace {

struct NormalsOptions {
    std::string dataset;
    std::string output;
    std::string albedo;
    std::string mask;
    std::string truth;
    bool linear = false;
    bool json = false;
    bool quiet = false;
};

Status runNormals(const NormalsOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "-o"); !s) return s;
    if (!o.albedo.empty())
        if (Status s = requireExtension(o.albedo, {"png"}, "--albedo"); !s) return s;
    Result<Dataset> dataset = openDatasetWithMask(o.dataset, o.mask);
    if (!dataset) return Error{dataset.error()};
    if (!dataset->fixedView())
        return Error{o.dataset + ": photometric stereo needs one camera; this dataset has several views"};
    std::vector<Image> decoded;
    std::vector<Direction> lights;
    for (const DatasetImage& info : dataset->images) {
        Result<Image> image = loadImage(info.path);
        if (!image) return Error{image.error()};
        if (!decoded.empty())
            if (Status s = requireSameSize(*image, info.path, decoded.front().width, decoded.front().height,
                                           dataset->images.front().path);
                !s)
                return s;
        decoded.push_back(std::move(*image));
        lights.push_back(info.light);
    }
    if (decoded.empty()) return Error{o.dataset + ": no images"};
    Result<Mask> mask = loadDatasetMask(*dataset, decoded.front().width, decoded.front().height);
    if (!mask) return Error{mask.error()};
    if (mask->count() == 0) return Error{o.dataset + ": the mask holds no pixel"};
    std::vector<const Image*> images;
    for (const Image& image : decoded) images.push_back(&image);
    Result<SurfaceMaps> maps = photometricStereo(images, lights, *mask, {.linear = o.linear});
    if (!maps) return Error{o.dataset + ": " + maps.error()};

    nlohmann::json out{{"normals", o.output}, {"images", decoded.size()}, {"unresolved", maps->unresolved}};
    std::string compared;
    if (!o.truth.empty()) {  // the estimate against a true normal map (same encoding)
        Result<Image> truth = loadImage(o.truth);
        if (!truth) return Error{truth.error()};
        if (Status s = requireSameSize(*truth, o.truth, maps->normals.width, maps->normals.height, o.dataset); !s)
            return s;
        if (truth->channels < 3) return Error{o.truth + ": a normal map has three channels"};
        const std::vector<double> angles = normalAngles(maps->normals, *truth, *mask);
        if (angles.empty()) return Error{o.truth + ": no normal to compare inside the mask"};
        double sum = 0;
        for (double a : angles) sum += a;
        const double mean = sum / static_cast<double>(angles.size()), median = angles[angles.size() / 2],
                     p90 = angles[angles.size() * 9 / 10];
        out["against_truth"] = {
            {"file", o.truth}, {"mean_degrees", mean}, {"median_degrees", median}, {"p90_degrees", p90}};
        char line[160];
        std::snprintf(line, sizeof line, "; against %s: mean %.2f, median %.2f, 90%% within %.2f degrees",
                      o.truth.c_str(), mean, median, p90);
        compared = line;
    }
    std::vector<Bytes> pngs{encodePng(maps->normals, 8)};
    std::vector<FileContents> files{{o.output, pngs.back().data(), pngs.back().size()}};
    if (!o.albedo.empty()) {
        pngs.push_back(encodePng(maps->albedo, 8));
        files.push_back({o.albedo, pngs.back().data(), pngs.back().size()});
        out["albedo"] = o.albedo;
    }
    if (Status s = writeFilesAtomically(files); !s) return s;
    if (o.json) {
        std::cout << jsonText(out);
    } else if (!o.quiet) {
        std::cout << "wrote " << o.output << (o.albedo.empty() ? "" : " and " + o.albedo) << " from " << decoded.size()
                  << " images (" << maps->unresolved << " texels left flat)" << compared << "\n";
    }
    return success();
}

}  // namespace

void addNormalsCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<NormalsOptions>();
    CLI::App* app = root.add_subcommand(
        "normals",
        "A capture's normal map and albedo by photometric stereo (shadows and highlights left out), for engines "
        "that light a flat texture with a normal map");
    app->add_option("DATASET", o->dataset, "a capture with one camera (.lp, folder, manifest)")->required();
    app->add_option("-o,--output", o->output,
                    "NORMALS.png: (n + 1) / 2 in R, G, B; x image right, y image up (OpenGL's convention), z out")
        ->required();
    app->add_option("--albedo", o->albedo, "ALBEDO.png: each channel's linear reflectance");
    app->add_option("--mask", o->mask, "the sample's pixels (non-zero); default the dataset's, else every pixel");
    app->add_option("--truth", o->truth, "TRUE.png: a true normal map (same encoding): print the angles between them");
    app->add_flag("--linear", o->linear, "the images hold linear values (default: 8-bit images are sRGB-encoded)");
    app->add_flag("--json", o->json, "print what was written (and the angles against --truth) as JSON");
    addQuietFlag(*app, o->quiet);
    commands.push_back({app, [o] { return runNormals(*o); }});
}

}  // namespace btflut::cli
