#include "cli/command.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "core/bank/bank_file.h"
#include "core/image/image.h"
#include "core/io/file_io.h"
#include "core/predict/learned_model.h"
#include "core/predict/predictor_fit.h"
#include "core/relight/engine_material.h"

namespace btflut::cli {

Status requireExtension(const std::string& path, const std::vector<std::string>& extensions, const std::string& what) {
    std::string ext = fileExtension(path);
    for (const std::string& e : extensions)
        if (ext == e) return success();
    std::string list;
    for (const std::string& e : extensions) list += (list.empty() ? "." : " or .") + e;
    return Error{path + ": " + what + " must be a " + list + " file"};
}

Result<SampleImage> loadSampleImage(const std::string& path, const std::string& maskPath) {
    Result<Image> image = loadImage(path);
    if (!image) return Error{image.error()};
    Mask mask = fullMask(image->width, image->height);
    if (!maskPath.empty()) {
        Result<Mask> loaded = loadMask(maskPath, image->width, image->height);
        if (!loaded) return Error{loaded.error()};
        mask = std::move(*loaded);
    }
    if (mask.count() == 0)
        return Error{(maskPath.empty() ? path : maskPath) + ": the image has no sample pixels (the mask is empty)"};
    return SampleImage{std::move(*image), std::move(mask)};
}

Result<BankAtDirection> loadBankAt(const std::string& bankPath, const std::string& light, const std::string& view) {
    Result<Direction> l = parseDirection(light, "--light");
    if (!l) return Error{l.error()};
    Result<Direction> v = view.empty() ? Result<Direction>(Direction{}) : parseDirection(view, "--view");
    if (!v) return Error{v.error()};
    Result<LutBank> bank = loadBank(bankPath);
    if (!bank) return Error{bank.error()};
    if (view.empty()) {
        v = bank->referenceView;
    } else if (bank->layers.size() == 1 && angleBetween(bank->layers[0].view, *v) > 1e-6) {
        // A bank measured from one view cannot change with the view: say so, never clamp silently.
        const Direction only = bank->layers[0].view;
        return Error{bankPath + ": the bank holds one view direction (" + std::to_string(only.thetaDegrees()) + ", " +
                     std::to_string(only.phiDegrees()) + " degrees); it cannot relight for --view " + view};
    }
    return BankAtDirection{std::move(*bank), *l, *v};
}

Result<Dataset> openDatasetWithMask(const std::string& path, const std::string& mask) {
    Result<Dataset> dataset = openDataset(path);
    if (dataset)
        for (const std::string& note : dataset->notes) std::cerr << "btflut: note: " << note << "\n";
    if (dataset && !mask.empty()) {
        if (Result<Bytes> exists = readFile(mask); !exists) return Error{exists.error()};
        dataset->maskPath = mask;
    }
    return dataset;
}

void addQuietFlag(CLI::App& app, bool& quiet, const std::string& what) { app.add_flag("-q,--quiet", quiet, what); }

void addLutImageOptions(CLI::App& app, int& depth, bool& noDither) {
    app.add_option("--depth", depth, "bits per sample of the PNG")
        ->check(CLI::IsMember({8, 16}))
        ->capture_default_str();
    app.add_flag("--no-dither", noDither,
                 "apply the plain LUT (by default each pixel is dithered within its grey level, "
                 "so the LUT can split a level's pixels and reproduce the target histogram closely)");
}

Result<FrameSize> parseFrameSize(const std::string& text) {
    FrameSize s;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &s.width, &x, &s.height, &extra) != 3 || x != 'x' || s.width <= 0 ||
        s.height <= 0 || s.width > 16384 || s.height > 16384)
        return Error{"--size '" + text + "': expected WxH with both within 1..16384"};
    return s;
}

Status checkTrainingTime(double seconds, const std::string& text) {
    if (seconds > kMostTrainingSeconds)
        return Error{"--budget '" + text + "': a training time of at most " +
                     std::to_string(static_cast<int>(kMostTrainingSeconds)) + " s (a day)"};
    return success();
}

double median(std::vector<double> v) {
    BTFLUT_CHECK(!v.empty());
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// A floor, a back wall and two side panels turned towards the camera, filling the view, each
// with the bank's material. Every quad faces the bench's lights (which come from the camera's
// side), so no mode draws a quad black: all modes shade the same fragments. Each further
// layer of the four lies 1 mm in front of the last and is drawn after it, so every layer
// passes the depth test: `layers` times the fragment work (overdraw).
Scene benchScene(const std::string& bank, int width, int height, const std::string& images, int layers) {
    Scene s;
    s.file = "bench";
    s.width = width;
    s.height = height;
    s.eye = {0, -3.2, 1.6};
    s.target = {0, 0, 0.6};
    s.fovDegrees = 60;
    s.materials["m"] = {bank, images};
    const std::vector<SceneQuad> quads{
        {"m", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 6, 6, 3, RenderMode::Lut},
        {"m", {0, 2, 1.5}, {0, -1, 0}, {1, 0, 0}, 6, 3, 2, RenderMode::Lut},
        {"m", {-2.2, 0.6, 1.5}, {0.7071, -0.7071, 0}, {0.7071, 0.7071, 0}, 4, 3, 2, RenderMode::Lut},
        {"m", {2.2, 0.6, 1.5}, {-0.7071, -0.7071, 0}, {0.7071, -0.7071, 0}, 4, 3, 2, RenderMode::Lut}};
    for (int layer = 0; layer < layers; ++layer)
        for (SceneQuad q : quads) {
            const double offset = 0.001 * layer;
            q.center = {q.center.x + offset * q.normal.x, q.center.y + offset * q.normal.y,
                        q.center.z + offset * q.normal.z};
            s.quads.push_back(q);
        }
    return s;
}

const std::array<Vec3, 2>& benchLights() {
    static const std::array<Vec3, 2> lights{toVector(Direction::fromDegrees(40, 250)),
                                            toVector(Direction::fromDegrees(55, 300))};
    return lights;
}

std::function<void(std::size_t, std::size_t)> terminalProgress(const std::string& label) {
    if (!::isatty(STDERR_FILENO)) return {};
    using Clock = std::chrono::steady_clock;
    // Drawn once the work has taken a second (quick runs stay quiet; BTFLUT_PROGRESS_AFTER
    // sets the seconds), with the time taken and an estimate of the time left from the rate so far.
    const char* after = std::getenv("BTFLUT_PROGRESS_AFTER");
    const double delay = after ? std::atof(after) : 1.0;
    return [label, delay, start = Clock::now(), shown = false](std::size_t done, std::size_t total) mutable {
        const double took = std::chrono::duration<double>(Clock::now() - start).count();
        if (!shown && took < delay) return;
        shown = true;
        const int width = 30;
        const int filled = static_cast<int>(width * std::min(done, total) / std::max<std::size_t>(total, 1));
        char left[48] = "";
        if (done > 0 && done < total)
            std::snprintf(left, sizeof left, ", about %.0f s left",
                          took * static_cast<double>(total - done) / static_cast<double>(done));
        std::fprintf(stderr, "\r%s [%s%s] %zu/%zu, %.0f s%s   ", label.c_str(), std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(), done, total, took, left);
        if (done >= total) std::fprintf(stderr, "\n");
    };
}

std::string unknownOption(const CLI::App& root, const CLI::App& sub, const std::vector<std::string>& args) {
    std::vector<std::string> known;
    auto learn = [&](const CLI::App& app) {
        for (const CLI::Option* option : app.get_options()) {
            for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
            for (const std::string& name : option->get_snames()) known.push_back("-" + name);
        }
    };
    learn(root);
    learn(sub);
    // Nested commands (bench render): their options too.
    const CLI::App* at = &sub;
    for (std::size_t k = 1; k < args.size(); ++k)
        for (const CLI::App* nested : at->get_subcommands([](const CLI::App*) { return true; }))
            if (nested->get_name() == args[k]) {
                learn(*nested);
                at = nested;
                break;
            }
    for (std::size_t k = 1; k < args.size(); ++k) {
        const std::string word = args[k].substr(0, args[k].find('='));
        if (word == "--") break;  // what follows is positional
        const bool option =
            word.size() > 1 && word[0] == '-' && !std::isdigit(static_cast<unsigned char>(word[1])) && word[1] != '.';
        if (!option || std::find(known.begin(), known.end(), word) != known.end()) continue;
        const std::string guess = closestName(word, known);
        return "unknown option " + word + (guess.empty() ? "" : " (did you mean " + guess + "?)");
    }
    return {};
}

int run(const std::vector<std::string>& args) {
    CLI::App root{
        "btflut: 3D textures in real time with histogram-matched look-up tables\n"
        "(van Ginneken, Koenderink & Dana, IJCV 1999). Angles are in degrees; a direction\n"
        "is THETA,PHI in the sample frame (z = surface normal, x = image right)."};
    root.name("btflut");
    root.footer(
        "Exit status: 0 done; 1 bad input (a missing or corrupt file, a value out of range, out of memory); 2 "
        "usage (an unknown command or option, a missing argument). compare: 0 within the tolerance, 1 outside, "
        "2 bad input.");
    root.set_version_flag("--version", std::string("btflut ") + BTFLUT_VERSION + " (.btflut format up to version " +
                                           std::to_string(kBankFormatVersion) + ", btflut.glsl version " +
                                           std::to_string(kShaderIncludeVersion) + ")");
    root.require_subcommand(1);
    root.fallthrough();  // root options may also follow the subcommand
    std::uint64_t maxPixels = kDefaultMaxImagePixels;
    root.add_option("--max-pixels", maxPixels,
                    "largest image (width x height) any input may declare; larger files are refused "
                    "from their header, before anything is allocated")
        ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40))
        ->capture_default_str();
    Commands commands;
    addHistCommand(root, commands);
    addFitCommand(root, commands);
    addOrientCommand(root, commands);
    addNormalsCommand(root, commands);
    addClassifyCommand(root, commands);
    addBakeCommand(root, commands);
    addRelightCommand(root, commands);
    addInfoCommand(root, commands);
    addExportCommand(root, commands);
    addMatchCommand(root, commands);
    addSimulateCommand(root, commands);
    addPlotCommand(root, commands);
    addSynthCommand(root, commands);
    addRenderCommand(root, commands);
    addBenchCommand(root, commands);
    addViewCommand(root, commands);
    addEvalCommand(root, commands);
    addCompareCommand(root, commands);

    if (args.empty()) {  // no command: what there is to run
        std::cout << root.help();
        return 0;
    }
    CLI::App* sub = nullptr;
    std::vector<std::string> names;
    for (CLI::App* candidate : root.get_subcommands([](const CLI::App*) { return true; })) {
        names.push_back(candidate->get_name());
        if (candidate->get_name() == args.front()) sub = candidate;
    }
    if (!sub && !args.front().empty() && args.front()[0] != '-') {
        const std::string guess = closestName(args.front(), names);
        std::cerr << "btflut: error: unknown command '" << args.front() << "'"
                  << (guess.empty() ? "" : " (did you mean " + guess + "?)") << "; see btflut --help\n";
        return 2;
    }
    std::string commandPath = sub ? sub->get_name() : "";  // with a nested command: "bench render"
    const CLI::App* deepest = sub;
    for (const CLI::App* at = sub; at;) {
        const CLI::App* next = nullptr;
        for (const CLI::App* nested : at->get_subcommands([](const CLI::App*) { return true; }))
            if (std::find(args.begin(), args.end(), nested->get_name()) != args.end()) next = nested;
        if (next) {
            commandPath += " " + next->get_name();
            deepest = next;
        }
        at = next;
    }
    // A value out of range or not a number is bad input, with the command's bad-input status.
    int badInputExit = 1;
    for (const Command& command : commands)
        if (command.app == deepest) badInputExit = command.errorExit;
    const std::string help = sub ? "btflut " + commandPath + " --help" : "btflut --help";
    if (sub)  // a misspelt option, before CLI11 reports the required option it hides
        if (const std::string unknown = unknownOption(root, *sub, args); !unknown.empty()) {
            std::cerr << "btflut " << commandPath << ": error: " << unknown << "; see " << help << "\n";
            return 2;
        }
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
    try {
        root.parse(reversed);
    } catch (const CLI::CallForHelp& e) {
        return root.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return root.exit(e);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return root.exit(e);
        std::cerr << "btflut" << (commandPath.empty() ? "" : " " + commandPath) << ": error: " << e.what() << " (see "
                  << help << ")\n";
        const bool badValue =
            dynamic_cast<const CLI::ValidationError*>(&e) || dynamic_cast<const CLI::ConversionError*>(&e);
        return badValue ? badInputExit : 2;
    }
    setMaxImagePixels(maxPixels);
    for (const Command& command : commands) {
        if (!command.app->parsed()) continue;
        // Expected failures arrive as Status; an exception here is a bug, but still ends in
        // one line and exit status 1, never an abort.
        Status status = success();
        try {
            status = command.run();
        } catch (const std::bad_alloc&) {
            status = Error{"out of memory"};
        } catch (const std::exception& e) {
            status = Error{std::string("unexpected error: ") + e.what()};
        }
        if (!status) {
            std::cerr << "btflut " << command.app->get_name() << ": error: " << status.error() << "\n";
            return command.errorExit;
        }
        return command.exitStatus ? command.exitStatus() : 0;
    }
    return 2;
}

}  // namespace btflut::cli
