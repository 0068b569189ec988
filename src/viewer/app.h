#pragma once
// The viewer of one opened input (a bank, a dataset or a scene file) in the window: its state
// and the methods its three parts share. viewer.cpp runs the frame loop (draw the panes,
// present, screenshots, scripted frames), panel.cpp draws the Dear ImGui panel and its plots,
// scene_input.cpp turns the mouse and keys over the scene into camera, light and compare
// changes. Internal to src/viewer; runViewer (viewer.h) is the way in.

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/lut_bank.h"
#include "core/histogram/histogram.h"
#include "gl/scene_renderer.h"
#include "gl/shape_renderer.h"
#include "gl/textures.h"
#include "viewer/camera.h"
#include "viewer/input.h"
#include "viewer/present.h"
#include "viewer/recent_files.h"
#include "viewer/viewer.h"
#include "viewer/window.h"

namespace btflut {

constexpr float kPanelWidth = 380;
constexpr int kHistogramBins = 64;

/// The label over a pane when several are side by side.
const char* paneLabel(RenderMode mode);

class Viewer {
public:
    Viewer(ViewerOptions options, ViewerInput input, Window& window)
        : m_options(std::move(options)),
          m_input(std::move(input)),
          m_window(window),
          m_orbit(Orbit::of(m_input.scene)) {}

    Status start();
    /// Runs until the window closes, the scripted frames are done, or a file is to be opened
    /// (openRequest()); `frame` counts on across viewers.
    Status run(int& frame);
    /// A file to open, from the panel, the recent files or a drop; empty if none.
    const std::string& openRequest() const { return m_openRequest; }
    void requestOpen(const std::string& path) { m_openRequest = path; }
    /// A line for the panel (an input that could not be opened); the viewer keeps running.
    void showMessage(const std::string& message) { m_message = message, m_openRequest.clear(); }
    const ViewerInput& input() const { return m_input; }
    Direction light() const { return m_light; }

private:
    enum class Geometry { Quad, Sphere, Cylinder };
    struct Pane {
        int x, y, width, height;  ///< window pixels, origin bottom left (GL)
        RenderMode mode;
    };
    std::vector<Pane> panes(int width, int height) const;
    /// Side by side, as the paper's Figs. 10-11: 2D texture mapping | LUT | the measurement.
    std::array<RenderMode, 3> splitModes() const {
        return {RenderMode::Brdf, RenderMode::Lut, m_haveImages ? RenderMode::Nearest : RenderMode::Flat};
    }
    Status renderPanes(int width, int height);
    /// The camera a pane shows: the orbit (3D) or the frontal orthographic view (2D).
    void paneCamera(const Pane& pane, Scene& scene) const;
    /// The composite images, allocated at the window's size.
    void allocateComposites(int width, int height);
    /// 2D mode is offered for a single quad (a bank or dataset), not for scene files.
    bool flatOffered() const { return m_input.singleQuad && m_bank; }
    void fitFlat(int width, int height);
    /// Shows a geometry (the sphere's or cylinder's renderer made on first use); on failure a
    /// line in the panel and the quad stays.
    bool setGeometry(Geometry geometry, int width, int height);
    bool curved() const { return m_geometry != Geometry::Quad; }
    /// Scene files: the material of the quad at window pixel (x, row), or empty.
    std::string materialAt(int x, int row, int width, int height) const;
    /// The bank the disk and the Material section describe: the hovered material's in a
    /// scene, else quad 0's.
    const LutBank* shownBank() const {
        const LutBank* hovered = m_hovered.empty() ? nullptr : m_renderer->bank(m_hovered);
        return hovered ? hovered : m_bank;
    }
    void updatePlots();
    bool panel(int width, int height);
    void filePanel();
    bool lightPanel();
    bool viewPanel(int width, int height);
    void materialPanel();
    bool sceneInput(int width, int height);
    Status saveScriptedFrame(int frame, int width, int height);
    Vec3 lightVector() const { return toVector(m_light); }
    Status screenshot(const std::string& path, int width, int height);
    void resetCamera(int width, int height);
    /// The panel's width; 0 while Tab hides it.
    int panelWidth() const { return m_panelVisible ? static_cast<int>(kPanelWidth) : 0; }
    void keyHelp();
    /// Whether the material has what a mode draws (a PTM, the measured images), and if not why.
    Status modeOffered(RenderMode m) const;
    /// A combo of the modes, those not offered greyed out; returns true when `mode` changed.
    bool modeCombo(const char* label, RenderMode& mode) const;
    void reportTiming() const;
    /// The wipe line or the lens's rim, and which mode is on each side.
    void compareOverlay(int height) const;

    ViewerOptions m_options;
    ViewerInput m_input;
    bool m_started = false;  ///< run() has set the camera up
    std::string m_openRequest, m_message;
    std::vector<double> m_frameMs;  ///< --timing: each frame's time, swap included
    std::array<char, 1024> m_pathField{};
    std::vector<std::string> m_recent = loadRecentFiles();
    Window& m_window;
    std::unique_ptr<SceneRenderer> m_renderer;
    const LutBank* m_bank = nullptr;  ///< quad 0's material, when visible
    bool m_panelVisible = true;
    bool m_helpVisible = false;
    LevelCounts m_referenceGrey;  ///< over the sample mask, when the dataset has one
    std::optional<Mask> m_mask;   ///< the dataset's sample mask (single-quad views)
    std::string m_hovered;        ///< scene files: the material of the quad under the cursor

    Direction m_light = Direction::fromDegrees(45, 30);
    Orbit m_orbit;
    int m_split = 1;
    std::array<RenderMode, 3> m_paneModes{RenderMode::Lut, RenderMode::Lut, RenderMode::Nearest};
    bool m_interpolate = true;
    bool m_havePtm = false, m_haveImages = false;

    Geometry m_geometry = Geometry::Quad;
    std::unique_ptr<ShapeRenderer> m_shapes;  ///< made when a sphere or cylinder is first shown
    double m_pointLight = 0;                  ///< > 0: a point light this far from the origin, in the light's direction
    bool m_flat = false;                      ///< 2D mode: frontal, orthographic, 1:1 at zoom 1
    FlatView m_flatView;
    RenderMode m_compareMode = RenderMode::Brdf;  ///< image B of the wipe or lens
    PresentSettings m_present;
    PresentPass m_presentPass;
    bool m_draggingWipe = false;
    float m_wipeAt =
        0.5f;  ///< the wipe line, a fraction of the panes' width: it stays put when Tab or a resize changes them

    GlTexture m_compositeColour, m_compositeColourB;  ///< A: the panes; B: the compare mode's
    GlFramebuffer m_composite, m_compositeB;
    int m_compositeWidth = 0, m_compositeHeight = 0;
    std::vector<float> m_renderedHistogram, m_targetHistogram, m_lutCurve;
    std::string m_provenance;
    double m_coverage = 0;  ///< of the hemisphere of lights, inside layer 0's measured hull
    double m_sceneMs = 0;
    std::string m_status;
    bool m_screenshotRequested = false;  ///< taken once the frame is drawn
};

}  // namespace btflut
