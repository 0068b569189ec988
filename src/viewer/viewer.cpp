#include "viewer/viewer.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/data/dataset.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"
#include "gl/gl_api.h"
#include "viewer/app.h"

namespace btflut {

namespace fs = std::filesystem;
using json = nlohmann::json;

const char* paneLabel(RenderMode mode) {
    switch (mode) {
        case RenderMode::Lut:
            return "LUT";
        case RenderMode::Brdf:
            return "2D texture mapping (brdf)";
        case RenderMode::Ptm:
            return "PTM";
        case RenderMode::Flat:
            return "flat texture";
        case RenderMode::Nearest:
            return "nearest measured image";
    }
    return "";
}

Status Viewer::start() {
    Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(m_input.scene, {.fixedCamera = false});
    if (!renderer) return Error{renderer.error()};
    m_renderer = std::move(*renderer);
    if (!m_input.scene.quads.empty()) m_bank = m_renderer->bank(m_input.scene.quads[0].material);
    if (m_bank) {
        const SceneMaterial& paths = m_input.scene.materials.at(m_input.scene.quads[0].material);
        if (m_input.singleQuad && !paths.images.empty()) {  // the dataset's sample mask, for the plots
            Result<Dataset> dataset = openDataset(paths.images);
            if (!dataset) return Error{dataset.error()};
            Result<Mask> mask = loadDatasetMask(*dataset, m_bank->reference.width, m_bank->reference.height);
            if (!mask) return Error{mask.error()};
            if (!dataset->maskPath.empty()) m_mask = std::move(*mask);
        }
        m_referenceGrey = countGreyLevels(
            m_bank->reference, m_mask ? *m_mask : fullMask(m_bank->reference.width, m_bank->reference.height));
        m_coverage = m_bank->lightCoverage(0);
        m_haveImages = !paths.images.empty();
        m_havePtm = m_bank->ptmInFile;
    }
    if (!m_options.light.empty()) {
        Result<Direction> light = parseDirection(m_options.light, "--light");
        if (!light) return Error{light.error()};
        m_light = *light;
    } else if (!m_input.singleQuad) {
        m_light = fromVector(m_input.scene.light);
    }
    Result<RenderMode> mode = parseRenderMode(m_options.mode);
    if (!mode) return Error{"--" + mode.error()};
    m_split = m_options.split;
    if (m_split > 1)
        m_paneModes = splitModes();
    else
        m_paneModes[0] = *mode;
    for (int p = 0; p < m_split; ++p)
        if (Status s = modeOffered(m_paneModes[static_cast<std::size_t>(p)]); !s) return s;
    // 2D by default where the input is one material seen from the front (a bank or dataset of
    // one frontal view); 3D for scene files and banks with several views.
    if (m_options.projection == "2d" && !flatOffered())
        return Error{m_input.scene.file + ": 2D mode shows one material (a bank or dataset), not a scene file"};
    m_flat = m_options.projection.empty() ? m_options.camera.empty() && flatOffered() && m_bank->layers.size() == 1 &&
                                                m_bank->layers[0].view.theta < M_PI / 180
                                          : m_options.projection == "2d";
    if (!m_options.compare.empty()) {
        Result<RenderMode> b = parseRenderMode(m_options.compareMode);
        if (!b) return Error{"--compare-" + b.error()};
        if (Status s = modeOffered(*b); !s) return s;
        m_compareMode = *b;
        m_present.compare =
            m_options.compare == "wipe" ? PresentSettings::Compare::Wipe : PresentSettings::Compare::Lens;
    }
    m_present.exposure = static_cast<float>(m_options.exposure);
    m_present.gamma = static_cast<float>(m_options.gamma);
    return success();
}

std::vector<Viewer::Pane> Viewer::panes(int width, int height) const {
    const int area = std::max(1, width - panelWidth());
    std::vector<Pane> out;
    for (int p = 0; p < m_split; ++p) {
        const int x0 = area * p / m_split, x1 = area * (p + 1) / m_split;
        out.push_back({x0, 0, std::max(1, x1 - x0), std::max(1, height), m_paneModes[static_cast<std::size_t>(p)]});
    }
    return out;
}

void Viewer::allocateComposites(int width, int height) {
    for (auto [colour, framebuffer] :
         {std::pair{&m_compositeColour, &m_composite}, {&m_compositeColourB, &m_compositeB}}) {
        *colour = allocateTexture2D(width, height, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // no mipmaps: complete for texelFetch
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        *framebuffer = makeFramebuffer();
        gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer->id());
        gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour->id(), 0);
    }
    m_compositeWidth = width;
    m_compositeHeight = height;
}

void Viewer::paneCamera(const Pane& pane, Scene& scene) const {
    if (m_flat) {
        m_flatView.apply(scene, scene.quads[0], pane.width, pane.height, m_bank->reference.width,
                         m_bank->reference.height);
        return;
    }
    scene.eye = m_orbit.eye();
    scene.target = m_orbit.target;
    scene.up = {0, 0, 1};
    scene.orthographicHeight = 0;
}

// Draws every pane into the composite image, and while comparing the same panes in the
// compare mode into the second (both kept between frames, so a frame where nothing changed
// only presents them).
Status Viewer::renderPanes(int width, int height) {
    if (width != m_compositeWidth || height != m_compositeHeight) allocateComposites(width, height);
    const bool comparing = m_present.compare != PresentSettings::Compare::Off && !curved();
    for (GLuint fb : {m_composite.id(), m_compositeB.id()}) {
        if (fb == m_compositeB.id() && !comparing) break;
        gl.BindFramebuffer(GL_FRAMEBUFFER, fb);
        gl.ClearColor(0.08f, 0.08f, 0.1f, 1);
        gl.Clear(GL_COLOR_BUFFER_BIT);
    }
    const auto start = std::chrono::steady_clock::now();
    m_renderer->setInterpolation(m_interpolate);
    const std::vector<Pane> all = panes(width, height);
    // The plots follow the LUT pane, or the first.
    std::size_t plottedPane = 0;
    for (std::size_t p = all.size(); p-- > 0;)
        if (all[p].mode == RenderMode::Lut) plottedPane = p;
    for (std::size_t p = 0; p < all.size(); ++p) {
        const Pane& pane = all[p];
        if (curved()) {  // the sphere or cylinder: mode lut, per fragment
            ShapeFrame frame{m_geometry == Geometry::Sphere ? Shape::Sphere : Shape::Cylinder,
                             m_orbit.eye(),
                             m_orbit.target,
                             {0, 0, 1},
                             m_input.scene.fovDegrees,
                             {}};
            const Vec3 l = lightVector();
            frame.light = {m_pointLight > 0, l, {l.x * m_pointLight, l.y * m_pointLight, l.z * m_pointLight}};
            if (Status s = m_shapes->draw(frame, pane.width, pane.height); !s) return s;
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m_shapes->framebuffer());
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m_composite.id());
            gl.BlitFramebuffer(0, 0, pane.width, pane.height, pane.x, pane.y, pane.x + pane.width, pane.y + pane.height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
            continue;
        }
        Scene camera = m_input.scene;
        paneCamera(pane, camera);
        m_renderer->setCamera(camera.eye, camera.target, camera.up, camera.orthographicHeight);
        if (Status s = m_renderer->resize(pane.width, pane.height); !s) return s;
        for (int image = 0; image < (comparing ? 2 : 1); ++image) {
            if (Status s = m_renderer->draw(lightVector(), image == 0 ? pane.mode : m_compareMode); !s) return s;
            if (p == plottedPane && image == 0) updatePlots();
            gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m_renderer->framebuffer());
            gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, image == 0 ? m_composite.id() : m_compositeB.id());
            gl.BlitFramebuffer(0, 0, pane.width, pane.height, pane.x, pane.y, pane.x + pane.width, pane.y + pane.height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
    }
    m_renderer->finish();
    m_sceneMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return success();
}

// The frames' times after the first (which compiles shaders and uploads textures).
void Viewer::reportTiming() const {
    if (m_frameMs.size() < 2) return;
    std::vector<double> ms(m_frameMs.begin() + 1, m_frameMs.end());
    std::sort(ms.begin(), ms.end());
    int width = 0, height = 0;
    glfwGetFramebufferSize(m_window.handle(), &width, &height);
    std::printf(
        "view timing: %zu frames at %dx%d (%s, %s%s): median %.2f ms, 90th percentile %.2f ms, slowest %.2f ms\n",
        ms.size(), width, height, m_flat ? "2D" : "3D", renderModeName(m_paneModes[0]),
        m_options.lightSweep ? ", the light moving every frame" : "", ms[ms.size() / 2], ms[ms.size() * 9 / 10],
        ms.back());
}

Status Viewer::screenshot(const std::string& path, int width, int height) {
    if (Status s = savePng(readFramebufferRgb(0, width, height), path); !s) return s;
    m_status = "saved " + path;
    return success();
}

// A scripted frame: the screenshot, its state, and a scene file that `btflut render` draws
// as the first pane shows it.
Status Viewer::saveScriptedFrame(int frame, int width, int height) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame-%04d", frame);
    const fs::path dir(m_options.screenshotDir);
    if (Status s = screenshot((dir / (std::string(stem) + ".png")).string(), width, height); !s) return s;
    const Pane pane = panes(width, height)[0];
    Scene scene = m_input.scene;
    scene.width = pane.width;
    scene.height = pane.height;
    paneCamera(pane, scene);
    scene.light = lightVector();
    scene.interpolateLuts = m_interpolate;
    for (SceneQuad& q : scene.quads) q.mode = pane.mode;
    if (!m_input.bakedBank.empty()) {  // the session's bank goes (or leaves the cache): keep a copy
        const fs::path kept = dir / "material.btflut";
        if (!fs::exists(kept)) {
            Result<Bytes> bytes = readFile(m_input.bakedBank);
            if (!bytes) return Error{bytes.error()};
            if (Status s = writeFileAtomically(kept.string(), *bytes); !s) return s;
        }
        for (auto& [name, material] : scene.materials)
            if (material.bank == m_input.bakedBank) material.bank = kept.string();
    }
    const std::string sceneFile = std::string(stem) + ".scene.json";
    if (Status s = writeFileAtomically((dir / sceneFile).string(), sceneToJson(scene, dir.string())); !s)
        return s;  // paths relative to it
    json state{{"frame", frame},
               {"light", {{"theta", m_light.thetaDegrees()}, {"phi", m_light.phiDegrees()}}},
               {"mode", renderModeName(pane.mode)},
               {"projection", m_flat ? "2d" : "3d"},
               {"input", m_input.scene.file},
               {"geometry", m_geometry == Geometry::Quad     ? "quad"
                            : m_geometry == Geometry::Sphere ? "sphere"
                                                             : "cylinder"},
               {"point_light", m_pointLight},
               {"grid_note", m_shapes ? m_shapes->gridNote() : ""},
               {"hovered_material", m_hovered},
               {"help_visible", m_helpVisible},
               {"message", m_message},
               {"here", m_provenance},  // "light clamped, view measured": how the frame's LUT was made
               {"zoom", m_flat ? json(m_flatView.zoom) : json()},
               {"compare", m_present.compare == PresentSettings::Compare::Off
                               ? json()
                               : json{{"kind", m_present.compare == PresentSettings::Compare::Wipe ? "wipe" : "lens"},
                                      {"mode", renderModeName(m_compareMode)},
                                      {"wipe_x", m_present.wipeX}}},
               {"scene", sceneFile},
               // PNG pixels, origin top left: where the scene pane and the panel are
               {"scene_viewport", {pane.x, height - pane.y - pane.height, pane.width, pane.height}},
               {"panel", {width - panelWidth(), 0, panelWidth(), height}}};
    if (m_flat) {  // where the image lies in the PNG (2D mode, the first pane)
        Scene camera = m_input.scene;
        paneCamera(pane, camera);
        const double texelsPerWorld = m_bank->reference.height / scene.quads[0].height;
        const double left = pane.width / 2.0 -
                            (camera.target.x - scene.quads[0].center.x) * texelsPerWorld * m_flatView.zoom -
                            m_bank->reference.width * m_flatView.zoom / 2;
        const double top = pane.height / 2.0 +
                           (camera.target.y - scene.quads[0].center.y) * texelsPerWorld * m_flatView.zoom -
                           m_bank->reference.height * m_flatView.zoom / 2;
        state["image_rect"] = {pane.x + left, height - pane.y - pane.height + top,
                               m_bank->reference.width * m_flatView.zoom, m_bank->reference.height * m_flatView.zoom};
    }
    return writeFileAtomically((dir / (std::string(stem) + ".json")).string(), jsonText(state));
}

namespace {

// The viewer that GLFW's drop callback hands paths to (one window, one viewer at a time).
Viewer* g_dropTarget = nullptr;

void onDrop(GLFWwindow*, int count, const char** paths) {
    if (g_dropTarget && count > 0) g_dropTarget->requestOpen(paths[0]);  // the first of several
}

}  // namespace

Status Viewer::run(int& frame) {
    GLFWwindow* window = m_window.handle();
    g_dropTarget = this;
    glfwSetDropCallback(window, onDrop);
    if (!m_started) {
        m_started = true;
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        resetCamera(width, height);
        if (m_flat && !m_options.zoom.empty() && m_options.zoom != "fit")
            m_flatView.zoom = std::stod(m_options.zoom);  // validated
        m_pointLight = m_options.pointLight;
        if (m_options.geometry != "quad" &&
            !setGeometry(m_options.geometry == "sphere" ? Geometry::Sphere : Geometry::Cylinder, width, height))
            return Error{m_input.scene.file + ": " + m_message};
        if (!m_options.camera.empty()) {  // validated by runViewer
            double azimuth = 0, elevation = 0, distance = m_orbit.distance;
            std::sscanf(m_options.camera.c_str(), "%lf,%lf,%lf", &azimuth, &elevation, &distance);
            m_orbit.azimuth = azimuth * M_PI / 180;
            m_orbit.elevation = elevation * M_PI / 180;
            m_orbit.distance = distance;
        }
    }
    bool dirty = true;
    int idleFrames = 0;
    const bool scripted = m_options.frames > 0;
    for (; !glfwWindowShouldClose(window) && m_openRequest.empty(); ++frame) {
        if (scripted && frame >= m_options.frames) break;
        const auto frameStart = std::chrono::steady_clock::now();
        if (scripted && frame == 1 && !m_options.injectDrop.empty()) {
            // A drop as the window system delivers it: through the callback GLFW holds.
            const GLFWdropfun registered = glfwSetDropCallback(window, nullptr);
            glfwSetDropCallback(window, registered);
            const char* paths[] = {m_options.injectDrop.c_str()};
            registered(window, 1, paths);
        }
        if (scripted || dirty || idleFrames < 3)
            glfwPollEvents();
        else
            glfwWaitEvents();  // nothing changes until an event: do not spin
        if (scripted && m_options.lightSweep) {
            // A spiral from near frontal to grazing: an isotropic material's look changes with
            // the light's elevation far more than with its azimuth.
            const double t = m_options.frames > 1 ? static_cast<double>(frame) / (m_options.frames - 1) : 0.0;
            m_light = Direction::fromDegrees(10 + 70 * t, 360.0 * frame / m_options.frames);
            dirty = true;
        }
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (width <= 0 || height <= 0) continue;  // minimised
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        if (scripted && !m_options.injectCursor.empty()) {  // as the backend would set it from the window system
            float x = 0, y = 0;
            if (std::sscanf(m_options.injectCursor.c_str(), "%f,%f", &x, &y) == 2)
                ImGui::GetIO().MousePos = ImVec2(x, y);
        }
        if (scripted && !m_options.injectKeys.empty()) {  // pressed at frame 1, released at frame 2
            for (const std::string& name : m_options.injectKeys) {
                const int key = name == "tab" ? GLFW_KEY_TAB : name == "f1" ? GLFW_KEY_F1 : GLFW_KEY_UNKNOWN;
                if (key != GLFW_KEY_UNKNOWN) ImGui::GetIO().KeysDown[key] = frame == 1;
            }
        }
        ImGui::NewFrame();
        dirty |= width != m_compositeWidth || height != m_compositeHeight;
        dirty |= sceneInput(width, height);
        m_present.wipeX = m_wipeAt * static_cast<float>(width - panelWidth());  // after Tab, or a resize
        // The scene first, so the panel shows its plots; what the panel changes is drawn in the
        // next frame (which follows at once: `dirty` polls instead of waiting).
        if (dirty) {
            if (Status s = renderPanes(width, height); !s) return s;
            idleFrames = 0;
        } else {
            ++idleFrames;
        }
        dirty = m_panelVisible && panel(width, height);
        if (!m_panelVisible)
            ImGui::GetForegroundDrawList()->AddText(ImVec2(static_cast<float>(width) - 190, 8),
                                                    IM_COL32(200, 200, 200, 255), "Tab: panel   F1: keys");
        keyHelp();
        compareOverlay(height);
        const std::vector<Pane> all = panes(width, height);
        for (const Pane& p : all)  // labels over the panes
            if (all.size() > 1)
                ImGui::GetForegroundDrawList()->AddText(ImVec2(static_cast<float>(p.x) + 8, 8),
                                                        IM_COL32(255, 255, 255, 255), paneLabel(p.mode));
        ImGui::Render();
        PresentSettings present = m_present;
        if (curved()) present.compare = PresentSettings::Compare::Off;  // the shapes draw mode lut only
        if (Status s = m_presentPass.draw({m_composite.id(), m_compositeColour.id()},
                                          {m_compositeB.id(), m_compositeColourB.id()}, present, width, height);
            !s)
            return s;
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (scripted && !m_options.screenshotDir.empty())
            if (Status s = saveScriptedFrame(frame, width, height); !s) return s;
        const bool last = scripted && frame + 1 == m_options.frames;
        if (m_screenshotRequested || (last && !m_options.screenshot.empty())) {
            const std::string path = !m_options.screenshot.empty() ? m_options.screenshot
                                                                   : "btflut-screenshot-" + std::to_string(::getpid()) +
                                                                         "-" + std::to_string(frame) + ".png";
            if (Status s = screenshot(path, width, height); !s) return s;
            m_screenshotRequested = false;
            idleFrames = 0;  // show the status line
        }
        glfwSwapBuffers(window);
        if (m_options.timing) {
            gl.Finish();  // the frame's time is the whole of its work, the GPU's included
            m_frameMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count());
        }
    }
    if (m_options.timing && m_openRequest.empty()) reportTiming();
    return success();
}

Status runViewer(const ViewerOptions& options) {
    if (options.split < 1 || options.split > 3) return Error{"--split must be 1, 2 or 3"};
    if (!options.screenshotDir.empty() && options.frames <= 0)
        return Error{"--screenshot-dir saves scripted frames: give --frames N"};
    if (!options.screenshotDir.empty()) {
        std::error_code ec;
        fs::create_directories(options.screenshotDir, ec);
        if (!fs::is_directory(options.screenshotDir, ec))
            return Error{options.screenshotDir + ": cannot create the folder for --screenshot-dir"};
    }
    if (!options.projection.empty() && options.projection != "2d" && options.projection != "3d")
        return Error{"--projection '" + options.projection + "': expected 2d or 3d"};
    if (!options.zoom.empty() && options.zoom != "fit") {
        char* end = nullptr;
        const double zoom = std::strtod(options.zoom.c_str(), &end);
        if (*end != '\0' || !(zoom >= 1.0 / 64 && zoom <= 64))
            return Error{"--zoom '" + options.zoom +
                         "': expected fit, or pixels per texel from 1/64 to 64 (1: one texel per pixel)"};
    }
    if (!options.compare.empty() && options.compare != "wipe" && options.compare != "lens")
        return Error{"--compare '" + options.compare + "': expected wipe or lens"};
    if (!std::isfinite(options.exposure) || std::abs(options.exposure) > 10)
        return Error{"--exposure must be a number of stops from -10 to 10"};
    if (!(options.gamma >= 0.1 && options.gamma <= 10)) return Error{"--gamma must be from 0.1 to 10"};
    if (!options.camera.empty()) {
        double azimuth = 0, elevation = 0, distance = 1;
        char extra = 0;
        const int n = std::sscanf(options.camera.c_str(), "%lf,%lf,%lf%c", &azimuth, &elevation, &distance, &extra);
        if ((n != 2 && n != 3) || !std::isfinite(azimuth) || !std::isfinite(elevation) || elevation < 3 ||
            elevation > 89 || !std::isfinite(distance) || distance <= 0)
            return Error{"--camera '" + options.camera +
                         "': expected AZIMUTH,ELEVATION[,DISTANCE] in degrees, elevation "
                         "3 to 89, distance > 0"};
    }
    // The window first: without a display there is nothing to do, and nothing to bake.
    Result<std::unique_ptr<Window>> window =
        Window::create(options.width, options.height, "btflut view", options.vsync);
    if (!window) return Error{window.error()};
    Result<ViewerInput> input = openInput(options);
    if (!input) return Error{input.error()};
    auto temporary = std::make_unique<TemporaryFile>();
    temporary->path = input->temporaryBank;
    glfwSetWindowTitle((*window)->handle(), input->title.c_str());
    rememberRecentFile(input->scene.file.empty() ? options.input : input->scene.file);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL((*window)->handle(), true);
    ImGui_ImplOpenGL3_Init("#version 330");
    Status result = success();
    {
        auto viewer = std::make_unique<Viewer>(options, std::move(*input), **window);
        result = viewer->start();
        for (int frame = 0; result;) {
            result = viewer->run(frame);
            if (!result || viewer->openRequest().empty()) break;
            // Another file: a new viewer for it, or a line in the current one's panel.
            ViewerOptions next = options;
            next.input = viewer->openRequest();
            next.images.clear();
            next.projection.clear();
            next.camera.clear();
            next.light =
                std::to_string(viewer->light().thetaDegrees()) + "," + std::to_string(viewer->light().phiDegrees());
            Result<ViewerInput> opened = openInput(next);
            if (!opened) {
                viewer->showMessage(opened.error());
                continue;
            }
            auto nextTemporary = std::make_unique<TemporaryFile>();
            nextTemporary->path = opened->temporaryBank;
            const std::string title = opened->title;
            auto fresh = std::make_unique<Viewer>(next, std::move(*opened), **window);
            if (Status s = fresh->start(); !s) {
                viewer->showMessage(s.error());
                continue;
            }
            viewer = std::move(fresh);
            temporary = std::move(nextTemporary);
            glfwSetWindowTitle((*window)->handle(), title.c_str());
            rememberRecentFile(next.input);
        }
        g_dropTarget = nullptr;
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return result;
}

}  // namespace btflut
