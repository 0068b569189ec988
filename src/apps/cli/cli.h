#pragma once
// The `btflut` command line: `run` parses, dispatches, and turns an Error into one line on
// stderr and exit status 1 (tests call it in-process), and what the commands share. Each
// subcommand lives in its own cmd_*.cpp and registers itself (command.h); only those include
// CLI11, which is slow to compile.

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/data/scene.h"
#include "core/histogram/histogram.h"
#include "core/io/closest_name.h"
#include "core/result.h"

namespace btflut::cli {

/// Runs btflut with arguments (without the program name); returns the exit status.
int run(const std::vector<std::string>& args);

// Shared by the commands.

/// Validates that `path` ends in one of `extensions` (lower case, no dot).
/// The masked, normalised grey histogram of every image of a dataset (`btflut hist`), or
/// three per image (R, G, B) with `rgb`; `mask` overrides the dataset's own when not empty.
Result<std::vector<HistogramRow>> datasetHistograms(const std::string& dataset, const std::string& mask, int bins,
                                                    bool rgb);

/// An image and the mask of its sample pixels (`maskPath`, or every pixel when empty);
/// refuses a mask without sample pixels.
struct SampleImage {
    Image image;
    Mask mask;
};
Result<SampleImage> loadSampleImage(const std::string& path, const std::string& maskPath);

Status requireExtension(const std::string& path, const std::vector<std::string>& extensions, const std::string& what);

/// A bank and the light and view to apply it at, from the command line's text
/// (THETA,PHI in degrees), each validated. An empty view means the bank's reference view; a
/// view that a one-view bank does not hold is refused.
struct BankAtDirection {
    LutBank bank;
    Direction light, view;
};
Result<BankAtDirection> loadBankAt(const std::string& bankPath, const std::string& light, const std::string& view);

/// Opens a dataset; a non-empty `mask` replaces the dataset's own mask (--mask).
Result<Dataset> openDatasetWithMask(const std::string& path, const std::string& mask);

/// --size's WxH, both within 1..16384.
struct FrameSize {
    int width = 0, height = 0;
};
Result<FrameSize> parseFrameSize(const std::string& text);

/// --budget's training time in seconds (bake, eval): at most kMostTrainingSeconds, a day;
/// `text` is the option's, which the error quotes.
Status checkTrainingTime(double seconds, const std::string& text);

/// The median of a non-empty list (the upper one of an even count).
double median(std::vector<double> values);

/// The benchmarks' scene (bench render, eval): four quads of one material filling a
/// width x height view, all lit by both benchLights(); `images` is the material's dataset
/// (for mode nearest), may be empty; `layers` copies of the four, each drawn over the last.
Scene benchScene(const std::string& bank, int width, int height, const std::string& images = {}, int layers = 1);
/// Two lights, alternated frame by frame, so that every frame re-blends.
const std::array<Vec3, 2>& benchLights();

/// A progress bar on stderr when it is a terminal, with the time taken and an estimate of
/// the time left, from the first second on; does nothing otherwise.
std::function<void(std::size_t, std::size_t)> terminalProgress(const std::string& label);

}  // namespace btflut::cli
