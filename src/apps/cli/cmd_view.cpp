// btflut view: the interactive viewer (src/viewer).
#include <cstdio>
#include <memory>

#include "cli/command.h"
#include "core/predict/predictor_fit.h"
#include "viewer/viewer.h"

namespace btflut::cli {

void addViewCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ViewerOptions>();
    CLI::App* app = root.add_subcommand(
        "view", "Explore a material in a window: move the light, switch modes, compare side by side (docs/viewer.md)");
    app->add_option(
        "INPUT", o->input,
        "M.btflut, a dataset (baked as bake would; kept for next time) or SCENE.json; default: the bundled material");
    app->add_option("--images", o->images, "with a bank: the dataset it was baked from (for mode nearest)");
    app->add_option("--mode", o->mode, "lut, brdf, ptm, flat or nearest")->capture_default_str();
    app->add_option("--split", o->split,
                    "panes side by side: 1; 2 (brdf | lut); 3 (brdf | lut | nearest, or flat without images)")
        ->check(CLI::Range(1, 3))
        ->capture_default_str();
    app->add_option("--light", o->light, "light THETA,PHI in degrees (world frame); default 45,30");
    app->add_option("--width", o->width, "window width")->check(CLI::Range(640, 8192))->capture_default_str();
    app->add_option("--height", o->height, "window height")->check(CLI::Range(400, 8192))->capture_default_str();
    auto size = std::make_shared<std::string>();
    app->add_option("--size", *size, "WxH: the window's width and height at once (640x400 to 8192x8192)");
    app->add_option("--camera", o->camera,
                    "AZIMUTH,ELEVATION[,DISTANCE]: the camera around the scene's target (degrees, scene units); "
                    "default the scene's");
    app->add_option(
        "--projection", o->projection,
        "2d: frontal and orthographic, pan and zoom (default for a material of one frontal view); 3d: orbit");
    app->add_option("--zoom", o->zoom, "2D: pixels per texel (1: one texel per pixel) or fit (default)");
    app->add_option("--compare", o->compare, "wipe or lens: the pane's mode against --compare-mode (key C)");
    app->add_option("--compare-mode", o->compareMode, "the mode in the wipe's right side or in the lens")
        ->capture_default_str();
    app->add_option("--exposure", o->exposure, "stops (in linear light)")->capture_default_str();
    app->add_option("--gamma", o->gamma, "display gamma on top of sRGB (1: none)")->capture_default_str();
    app->add_option("--geometry", o->geometry, "quad; sphere or cylinder (a bank of LUTs, per fragment; key G)")
        ->check(CLI::IsMember({"quad", "sphere", "cylinder"}))
        ->capture_default_str();
    app->add_option("--point-light", o->pointLight,
                    "sphere and cylinder: a point light this far from the centre (0: directional)")
        ->check(CLI::Range(0.0, 100.0));
    app->add_flag("--timing", o->timing, "scripted: print the median frame time at exit (the first frame left out)");
    app->add_option("--inject-drop", o->injectDrop,
                    "scripted (tests): at frame 1, PATH is dropped on the window through GLFW's drop callback");
    app->add_option("--inject-key", o->injectKeys, "scripted (tests): tab or f1, pressed at frame 1")
        ->check(CLI::IsMember({"tab", "f1"}));
    app->add_option("--inject-cursor", o->injectCursor, "scripted (tests): X,Y, the mouse's place in the window");
    app->add_flag_callback(
        "--no-vsync", [o] { o->vsync = false; }, "draw as fast as possible");
    app->add_option("--frames", o->frames, "scripted: draw N frames, then exit")->check(CLI::Range(1, 100000));
    app->add_flag("--light-sweep", o->lightSweep, "scripted: the light spirals from theta 10 to 80 over the frames");
    app->add_option("--screenshot", o->screenshot, "PNG of the last scripted frame; interactively the S key's file");
    app->add_option("--screenshot-dir", o->screenshotDir,
                    "scripted: every frame as frame-NNNN.png with its state (.json) and scene (.scene.json)");
    app->add_option("--references", o->bake.references,
                    "with a dataset: references blended per light (bake --references)")
        ->check(CLI::Range(1, 255));
    app->add_option("--regions", o->bake.regions, "with a dataset: regions matched apart (bake --regions)")
        ->check(CLI::Range(1, 255));
    auto colour = std::make_shared<std::string>("grey");
    auto predictor = std::make_shared<std::string>("auto");
    app->add_option("--colour", *colour, "with a dataset: grey, rgb or lrgb (bake --colour)")
        ->check(CLI::IsMember({"grey", "rgb", "lrgb"}));
    app->add_option("--predictor", *predictor,
                    "with a dataset: auto (the default: what `bake DATASET` writes, chosen by validation), "
                    "references, a light model: ptm, hsh2, hsh3, rbfN, blnN, or a learned one: neuralN (bake "
                    "--predictor)");
    app->add_flag("--rebake", o->rebake,
                  "with a dataset: bake it again, not the bank kept from an earlier view of it "
                  "($XDG_CACHE_HOME/btflut/view)");
    commands.push_back({app, [o, colour, predictor, size, app] {
                            if (!size->empty()) {
                                int w = 0, h = 0;
                                char extra = 0;
                                if (std::sscanf(size->c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 640 || w > 8192 ||
                                    h < 400 || h > 8192)
                                    return Status{Error{"--size '" + *size + "': expected WxH, 640x400 to 8192x8192"}};
                                o->width = w;
                                o->height = h;
                            }
                            o->bake.colour = *colour == "rgb"    ? ColourMode::Rgb
                                             : *colour == "lrgb" ? ColourMode::Lrgb
                                                                 : ColourMode::Grey;
                            // auto, as bake: unless references or a predictor are named.
                            o->validate = *predictor == "auto" && app->count("--references") == 0;
                            if (*predictor != "references" && *predictor != "auto") {
                                std::optional<Result<FitPointer>> fit = predictorFitNamed(*predictor);
                                if (!fit)
                                    return Status{Error{"--predictor '" + *predictor +
                                                        "': expected auto, references, a basis (ptm, hsh, rbf, bln) "
                                                        "or a learned model (neuralN)"}};
                                if (!*fit) return Status{Error{"--predictor " + fit->error()}};
                                o->bake.fit = **fit;
                            }
                            return runViewer(*o);
                        }});
}

}  // namespace btflut::cli
