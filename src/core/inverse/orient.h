#pragma once
// Shape from texture (paper section 6.4): the orientation of a sample relative to a known
// light (or view) direction from one image's grey-level histogram.
//
//   Result<MaterialHistograms> m = loadMaterial("concrete.json");
//   Result<Orientation> o = estimateOrientation(imageHistogram, *m, light, Known::Light, tolerance);
//   o->candidates.front().normal;   // best first
//
// Frames. With a known light, the frame is the camera's: z towards the camera, the light at
// `known`; the sample's normal n is sought in it, and the sample sees the view along n's
// frame's z. With a known view, the frame is the light's: z towards the light. A sample
// frame's x axis is the frame's x turned with the normal (the smallest rotation taking z to
// n), which is all an isotropic material needs.
//
// Method: the histogram's earth mover's distance to the material's prediction over a grid
// of normals (tilt up to 85 degrees), then a pattern search from the best normal of each
// candidate region. Regions are the connected sets of normals whose distance is within
// `tolerance` of the best: the histogram cannot tell the normals of one region apart, and
// several regions are several answers (an isotropic material is always ambiguous under the
// mirror through the plane of camera and light). A candidate's uncertainty is the largest
// angle between its normal and another of its region; regions closer than their
// uncertainties are merged into one candidate.

#include <vector>

#include "core/inverse/material_histograms.h"

namespace btflut {

enum class Known { Light, View };

struct OrientationCandidate {
    Direction normal;                ///< in the known direction's frame (see above)
    Direction light, view;           ///< in the sample's frame
    double distance = 0;             ///< earth mover's distance of the histograms
    double uncertainty = 0;          ///< radians: the largest angle to another normal of its region
    double tiltUncertainty = 0;      ///< radians: the largest tilt difference within its region
    bool azimuthDetermined = true;   ///< false: its region runs round the pole (a light at the camera, say)
    std::vector<std::size_t> cells;  ///< while searching: the region's grid cells
};

struct Orientation {
    std::vector<OrientationCandidate> candidates;  ///< best first
    double tolerance = 0;
};

struct OrientOptions {
    double tiltStep = 2 * kDegree;
    double azimuthStep = 4 * kDegree;
    double maxTilt = 85 * kDegree;
    int bins = 64;
};

/// `histogram`: the image's normalised histogram (options.bins bins). `tolerance`: the
/// distance the image's own sampling allows (histogramTolerance). Errors: a histogram of
/// the wrong size or empty, a known direction below the horizon.
Result<Orientation> estimateOrientation(const std::vector<double>& histogram, const MaterialHistograms& material,
                                        Direction known, Known which, double tolerance,
                                        const OrientOptions& options = {});

/// How far an image's histogram could be from the material's by chance: half the mean earth
/// mover's distance between the histograms of its halves (left against right, top against
/// bottom) over the mask (two halves differ by about twice what the whole differs from its
/// expectation); at least 1/(4 bins).
double histogramTolerance(const Image& image, const Mask& mask, int bins);

}  // namespace btflut
