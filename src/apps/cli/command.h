#pragma once
// What a subcommand's file (cmd_*.cpp) sees: CLI11, the registration of each subcommand on
// the root app, and the options several commands share.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cli/cli.h"

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
/// `bench decoder` (bench_decoder.cpp) and `bench levels` (bench_levels.cpp), under `bench`.
void addBenchDecoderCommand(CLI::App& bench, Commands& commands);
void addBenchLevelsCommand(CLI::App& bench, Commands& commands);
void addBenchRenderCommand(CLI::App& bench, Commands& commands);
/// What the GL benches beside `bench render` take alike: --frames (`what` each is) per row and
/// round, --repeat rounds, --backend, --json.
struct GlBenchOptions {
    int frames = 5;
    int repeat = 3;
    std::string backend = "auto";
    bool json = false;
};
void addGlBenchOptions(CLI::App& app, GlBenchOptions& o, const std::string& what);
void addViewCommand(CLI::App& root, Commands& commands);
void addEvalCommand(CLI::App& root, Commands& commands);
void addOrientCommand(CLI::App& root, Commands& commands);
void addNormalsCommand(CLI::App& root, Commands& commands);
void addClassifyCommand(CLI::App& root, Commands& commands);
void addCompareCommand(CLI::App& root, Commands& commands);

/// -q,--quiet, alike on every command that prints progress or what it wrote: only errors
/// (on stderr) remain, and the exit status. `what`: what it leaves out, where that is more.
void addQuietFlag(CLI::App& app, bool& quiet, const std::string& what = "print nothing but errors");

/// The options of commands that write a LUT-mapped image: --depth 8|16 and --no-dither.
void addLutImageOptions(CLI::App& app, int& depth, bool& noDither);

/// "unknown option --ligth (did you mean --light?)" for the first option of `args` (the
/// command line after the program name) that neither `root` nor `sub` knows; empty if none.
std::string unknownOption(const CLI::App& root, const CLI::App& sub, const std::vector<std::string>& args);

}  // namespace btflut::cli
