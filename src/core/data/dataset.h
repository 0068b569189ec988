#pragma once
// A dataset: images of one material, each with the light and view direction it was taken
// under, and an optional sample mask. Four on-disk forms are recognised from one path:
//
//   btflut manifest  FILE.json, or a folder holding btflut-dataset.json   (docs/datasets.md)
//   RTI capture      FILE.lp, or a folder holding exactly one .lp file    (fixed frontal view;
//                    a mask.png beside the .lp file is its mask)
//   photometric set  a folder with lights.txt, NAME.K.ext, NAME.mask.ext  (fixed frontal view)
//   Bonn UBO2003     a folder of "tl015 pl000 tv000 pv000.jpg" images
//
//   Result<Dataset> ds = openDataset("../shared/data/psm-rock");
//   for (const DatasetImage& im : ds->images) { ... loadImage(im.path) ... }
//
// Opening parses and validates the description (and finds an .lp file's images); images are
// decoded by whoever streams through them (a Bonn BTF holds thousands of large images).

#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/histogram/histogram.h"
#include "core/image/image.h"
#include "core/result.h"

namespace btflut {

struct DatasetImage {
    std::string name;  ///< short label (file name without extension)
    std::string path;  ///< file to decode
    Direction light;   ///< direction to the light, sample frame
    Direction view;    ///< direction to the camera, sample frame
    int line = 0;      ///< the line of the description that lists it (.lp files; 0: none)
};

struct Dataset {
    std::string source;    ///< the path it was opened from
    std::string format;    ///< "manifest", "rti", "psm" or "bonn"
    std::string maskPath;  ///< empty when the whole image is the sample
    std::vector<DatasetImage> images;
    /// What opening adjusted, one line each, for the command line to say once: light vectors
    /// normalised (within kRoundedLightTolerance of unit length), image paths not found as
    /// written and found by their file name beside the .lp file.
    std::vector<std::string> notes;
    /// True when every image shows the sample in one frame, whatever its view (rectified BTFs:
    /// UBO2003, and btflut synth's images, rendered in the frontal frame): pixels compare
    /// across views. Manifests say so with "rectified": true.
    bool rectified = false;

    /// True when every image shares one view direction (a fixed camera).
    bool fixedView() const;
    /// The view holding the fewest distinct light directions, and how many it holds
    /// (directions within 1e-6 rad are one): a bank of a layer per view follows the light
    /// with 3 or more in each.
    std::pair<Direction, std::size_t> fewestLightsPerView() const;
};

/// True for the extensions (lower case, no dot) of the image files btflut reads.
bool isImageExtension(const std::string& ext);

/// Recognises the dataset form at `path` and parses it. Errors name the file (and line)
/// and the problem: unreadable, malformed, NaN or non-unit light vectors, lights at or
/// below the horizon, missing images.
Result<Dataset> openDataset(const std::string& path);

/// The dataset's mask for its images of width x height (every pixel when it has none).
Result<Mask> loadDatasetMask(const Dataset& dataset, int width, int height);

/// The normalised `bins`-bin histogram of every image over the dataset's mask: its grey value,
/// or (rgb) one row per channel named NAME:R, NAME:G, NAME:B. Images are decoded in parallel;
/// errors name the file (corrupt, another size, grey where rgb is asked).
Result<std::vector<HistogramRow>> histogramsOf(const Dataset& dataset, int bins, bool rgb);

/// Refuses `image` (decoded from `path`) unless it is width x height like the first
/// image `firstPath`.
Status requireSameSize(const Image& image, const std::string& path, int width, int height,
                       const std::string& firstPath);

// The parsers behind openDataset, exposed for tests. `file` names the source in errors;
// `folder` is where relative image paths start.
Result<Dataset> parseManifest(const std::string& text, const std::string& file, const std::string& folder);
/// Light vectors within kRoundedLightTolerance of unit length are normalised (.lp: noted in
/// Dataset::notes; lights.txt: counted in `normalised`).
Result<Dataset> parseLpFile(const std::string& text, const std::string& file, const std::string& folder);
Result<std::vector<Direction>> parseLightsTxt(const std::string& text, const std::string& file,
                                              std::size_t* normalised = nullptr);

/// Light and view of a Bonn UBO2003 file name ("tl015 pl000 tv000 pv000.jpg"); also
/// accepts "_" between the fields. Returns an error for any other name.
Result<DatasetImage> parseBonnName(const std::string& fileName, const std::string& folder);

}  // namespace btflut
