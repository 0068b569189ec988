#pragma once
// `btflut view`: a window with the scene and a Dear ImGui panel for exploring a material's
// appearance as the light moves (docs/viewer.md).
//
//   ViewerOptions o;  o.input = "rock.btflut";
//   Status s = runViewer(o);   // returns when the window closes (or after o.frames)

#include <string>
#include <vector>

#include "core/bake/bake.h"
#include "core/bank/lut_bank.h"

#include "core/result.h"

namespace btflut {

struct ViewerOptions {
    std::string input;   ///< M.btflut, a dataset, or SCENE.json; empty: the bundled default material
    std::string images;  ///< with a bank: the dataset it was baked from (mode nearest)
    int width = 1280, height = 800;
    std::string mode = "lut";
    std::string light;  ///< THETA,PHI (degrees, world frame); empty: 45,30
    int split = 1;      ///< panes side by side: 1, 2 (brdf | lut) or 3 (brdf | lut | nearest)
    bool vsync = true;
    // Scripted runs (tests, demos): a fixed number of frames, then exit.
    int frames = 0;             ///< 0: interactive
    bool lightSweep = false;    ///< with frames: the light spirals from theta 10 to 80 over the frames
    std::string screenshot;     ///< PNG of the last frame (and the S key's target interactively)
    std::string screenshotDir;  ///< every scripted frame: frame-NNNN.png, .json (state), .scene.json (created)
    std::string camera;  ///< AZIMUTH,ELEVATION[,DISTANCE] (degrees; scene units) around the target; empty: the scene's
    std::string projection;  ///< "2d" (frontal, orthographic), "3d"; empty: 2d for a material of one frontal view
    std::string zoom;        ///< 2D: pixels per texel ("1": one texel per pixel), or "fit" (the default)
    std::string compare;     ///< "wipe" or "lens" between the pane's mode and `compareMode`; empty: off
    std::string compareMode = "brdf";
    double exposure = 0;            ///< stops
    double gamma = 1;               ///< display gamma on top of sRGB
    std::string geometry = "quad";  ///< quad, sphere or cylinder (the last two: mode lut per fragment)
    double pointLight = 0;  ///< > 0: sphere and cylinder lit by a point light this far away, in the light's direction
    bool timing = false;    ///< scripted: print the frames' median and 90th percentile times at exit
    std::string injectDrop;
    std::vector<std::string> injectKeys;  ///< scripted: keys pressed at frame 1 (tab, f1)
    std::string injectCursor;  ///< scripted: X,Y (window pixels from the top left): where the mouse is   ///< scripted:
                               ///< at frame 1 this path is dropped on the window (through GLFW's callback)
    /// A dataset is baked with these (references, regions, colour, predictor).
    BakeOptions bake;
    bool rebake = false;  ///< with a dataset: bake it again, not the cached bank (bake_cache.h)
    bool validate =
        true;  ///< with a dataset: bake what `bake` makes by default (bakeAuto), unless `bake` names a predictor
};

Status runViewer(const ViewerOptions& options);

}  // namespace btflut
