#pragma once
// A normal map and an albedo from a capture (Woodham's photometric stereo, robust to shadows
// and highlights), as RTI tools give beside their bases (relight-cli, RTIBuilder): for engines
// that light a flat texture with a normal map, and to check a capture.
//
//   Result<SurfaceMaps> maps = photometricStereo(images, lights, mask, {});
//   savePng(maps->normals, "normals.png");   // (n + 1) / 2: x image right, y image up, z out
//
// Per texel, the samples are linearised (sRGB-encoded 8-bit images by default), sorted by
// brightness, and the darkest (cast and attached shadows) and brightest (highlights) left out;
// the rest fit I = rho (n . l) by least squares. A texel whose kept lights do not span three
// directions (lights on a line, too few), or whose fit is zero, gets the flat normal (0, 0, 1)
// and albedo 0, and is counted.

#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"
#include "core/result.h"

namespace btflut {

struct PhotometricStereoOptions {
    double shadowFraction = 0.25;     ///< the darkest share of a texel's samples left out
    double highlightFraction = 0.10;  ///< the brightest share left out
    bool linear = false;              ///< the images hold linear values (else 8-bit ones are sRGB-encoded)
    int threads = 0;                  ///< 0: all cores
};

struct SurfaceMaps {
    Image normals;               ///< RGB, (n + 1) / 2; outside the mask (0.5, 0.5, 1)
    Image albedo;                ///< the images' channels, linear reflectance (rho, clamped to 1)
    std::size_t unresolved = 0;  ///< texels in the mask left flat (degenerate lights or black)
};

/// The maps of images of one size (at least three, lights above the horizon). Errors say why
/// the set cannot be solved (fewer than three lights, lights that span no plane).
Result<SurfaceMaps> photometricStereo(const std::vector<const Image*>& images, const std::vector<Direction>& lights,
                                      const Mask& mask, const PhotometricStereoOptions& options);

/// Angles in degrees between two normal maps' normals over the mask, sorted (for the mean,
/// median and percentiles of an estimate against the truth).
std::vector<double> normalAngles(const Image& a, const Image& b, const Mask& mask);

}  // namespace btflut
