// btflut orient: shape from texture (paper 6.4), a sample's orientation from one image's histogram.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "core/inverse/orient.h"
#include "core/io/json_text.h"

namespace btflut::cli {

namespace {

struct OrientCommandOptions {
    std::string image;
    std::string material;
    std::string light;
    std::string view;
    std::string mask;
    bool json = false;
};

Status runOrient(const OrientCommandOptions& o) {
    if (!o.light.empty() && !o.view.empty()) return Error{"give --light or --view, not both"};
    const Known which = o.view.empty() ? Known::Light : Known::View;
    Result<Direction> known = parseDirection(o.view.empty() ? (o.light.empty() ? "0,0" : o.light) : o.view,
                                             which == Known::Light ? "--light" : "--view");
    if (!known) return Error{known.error()};
    if (known->thetaDegrees() >= 90)
        return Error{std::string(which == Known::Light ? "--light" : "--view") +
                     " must be above the horizon (theta < 90)"};
    Result<MaterialHistograms> material = loadMaterial(o.material);
    if (!material) return Error{material.error()};
    Result<SampleImage> sample = loadSampleImage(o.image, o.mask);
    if (!sample) return Error{sample.error()};

    const OrientOptions options;
    const std::vector<double> histogram = binHistogram(countGreyLevels(sample->image, sample->mask), options.bins);
    const double tolerance = histogramTolerance(sample->image, sample->mask, options.bins);
    Result<Orientation> orientation = estimateOrientation(histogram, *material, *known, which, tolerance, options);
    if (!orientation) return Error{o.image + ": " + orientation.error()};

    const char* frame = which == Known::Light ? "camera" : "light";
    if (o.json) {
        nlohmann::json out{{"image", o.image},
                           {"material", o.material},
                           {"frame", frame},
                           {which == Known::Light ? "light" : "view", directionJson(*known)},
                           {"tolerance", orientation->tolerance},
                           {"candidates", nlohmann::json::array()}};
        for (const OrientationCandidate& c : orientation->candidates)
            out["candidates"].push_back({{"normal", directionJson(c.normal)},
                                         {"light", directionJson(c.light)},
                                         {"view", directionJson(c.view)},
                                         {"emd", c.distance},
                                         {"uncertainty", c.uncertainty / kDegree},
                                         {"tilt_uncertainty", c.tiltUncertainty / kDegree},
                                         {"azimuth_determined", c.azimuthDetermined}});
        std::cout << jsonText(out);
        return success();
    }
    char line[320];
    std::snprintf(line, sizeof line,
                  "%s: the sample's normal in the %s's frame (z towards the %s), %s at (%.1f, %.1f):\n",
                  o.image.c_str(), frame, frame, which == Known::Light ? "light" : "view", known->thetaDegrees(),
                  known->phiDegrees());
    std::cout << line;
    for (std::size_t k = 0; k < orientation->candidates.size(); ++k) {
        const OrientationCandidate& c = orientation->candidates[k];
        std::snprintf(line, sizeof line,
                      "  %s tilt %.1f +- %.1f, azimuth %.1f%s (normal within %.1f degrees); in the sample: light "
                      "(%.1f, %.1f), view (%.1f, %.1f); EMD %.4f\n",
                      k == 0 ? "best:     " : "candidate:", c.normal.thetaDegrees(), c.tiltUncertainty / kDegree,
                      c.normal.phiDegrees(), c.azimuthDetermined ? "" : " (not determined)", c.uncertainty / kDegree,
                      c.light.thetaDegrees(), c.light.phiDegrees(), c.view.thetaDegrees(), c.view.phiDegrees(),
                      c.distance);
        std::cout << line;
    }
    std::snprintf(line, sizeof line,
                  "%zu candidate(s)%s: normals whose histograms are within EMD %.4f of the best (half the difference "
                  "between the image's own halves)\n",
                  orientation->candidates.size(),
                  orientation->candidates.size() > 1 ? ", the histogram cannot decide between them" : "",
                  orientation->tolerance);
    std::cout << line;
    return success();
}

}  // namespace

void addOrientCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<OrientCommandOptions>();
    CLI::App* app = root.add_subcommand(
        "orient",
        "Shape from texture: a sample's orientation relative to a known light (or view) from one image's histogram");
    app->add_option("IMAGE", o->image, "the image of the sample")->required();
    app->add_option("--material", o->material,
                    "the material: a fitted model's PARAMS.json (btflut fit) or a bank (.btflut)")
        ->required();
    app->add_option("--light", o->light,
                    "THETA,PHI: the light's direction seen from the camera (z towards the camera, x right, y up); "
                    "default 0,0 (at the camera)");
    app->add_option("--view", o->view,
                    "instead: THETA,PHI, the camera's direction seen from the light (z towards the light)");
    app->add_option("--mask", o->mask, "the sample's pixels (non-zero) in the image; default every pixel");
    app->add_flag("--json", o->json, "print JSON");
    commands.push_back({app, [o] { return runOrient(*o); }});
}

}  // namespace btflut::cli
