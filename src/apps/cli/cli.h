#pragma once
// The `btflut` command line. Each subcommand lives in its own cmd_*.cpp and registers
// itself on the root app; `run` parses, dispatches, and turns an Error into one line on
// stderr and exit status 1. Tests call `run` in-process.

#include <CLI/CLI.hpp>
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

/// A registered subcommand: its CLI11 app and what to do once it parsed.
struct Command {
    CLI::App* app;
    std::function<Status()> run;
    int errorExit = 1;                ///< the exit status of an Error
    std::function<int()> exitStatus;  ///< after success (empty: 0); compare's 1 outside its tolerance
};
using Commands = std::vector<Command>;

void addHistCommand(CLI::App& root, Commands& commands);
void addFitCommand(CLI::App& root, Commands& commands);
void addBakeCommand(CLI::App& root, Commands& commands);
void addRelightCommand(CLI::App& root, Commands& commands);
void addInfoCommand(CLI::App& root, Commands& commands);
void addExportCommand(CLI::App& root, Commands& commands);
void addMatchCommand(CLI::App& root, Commands& commands);
void addSimulateCommand(CLI::App& root, Commands& commands);
void addPlotCommand(CLI::App& root, Commands& commands);
void addSynthCommand(CLI::App& root, Commands& commands);
void addRenderCommand(CLI::App& root, Commands& commands);
void addBenchCommand(CLI::App& root, Commands& commands);
void addViewCommand(CLI::App& root, Commands& commands);
void addEvalCommand(CLI::App& root, Commands& commands);
void addOrientCommand(CLI::App& root, Commands& commands);
void addClassifyCommand(CLI::App& root, Commands& commands);
void addCompareCommand(CLI::App& root, Commands& commands);

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

/// -q,--quiet, alike on every command that prints progress or what it wrote: only errors
/// (on stderr) remain, and the exit status. `what`: what it leaves out, where that is more.
void addQuietFlag(CLI::App& app, bool& quiet, const std::string& what = "print nothing but errors");

/// The options of commands that write a LUT-mapped image: --depth 8|16 and --no-dither.
void addLutImageOptions(CLI::App& app, int& depth, bool& noDither);

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

/// "unknown option --ligth (did you mean --light?)" for the first option of `args` (the
/// command line after the program name) that neither `root` nor `sub` knows; empty if none.
std::string unknownOption(const CLI::App& root, const CLI::App& sub, const std::vector<std::string>& args);

/// The median of a non-empty list (the upper one of an even count).
double median(std::vector<double> values);

/// The benchmarks' scene (bench render, eval): four quads of one material filling a
/// width x height view, all lit by both benchLights(); `images` is the material's dataset
/// (for mode nearest), may be empty; `layers` copies of the four, each drawn over the last.
Scene benchScene(const std::string& bank, int width, int height, const std::string& images = {}, int layers = 1);
/// Two lights, alternated frame by frame, so that every frame re-blends.
const std::array<Vec3, 2>& benchLights();

/// A progress bar on stderr when it is a terminal; does nothing otherwise.
std::function<void(std::size_t, std::size_t)> terminalProgress(const std::string& label);

}  // namespace btflut::cli
