#include "viewer/viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/histogram/histogram.h"
#include "core/io/json_text.h"
#include "gl/gl_api.h"
#include "gl/scene_renderer.h"
#include "gl/shape_renderer.h"
#include "gl/textures.h"
#include "viewer/camera.h"
#include "viewer/input.h"
#include "viewer/present.h"
#include "viewer/recent_files.h"
#include "viewer/widgets.h"
#include "viewer/window.h"

namespace btflut {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr float kPanelWidth = 380;
constexpr int kHistogramBins = 64;
const RenderMode kModes[] = {RenderMode::Lut, RenderMode::Brdf, RenderMode::Ptm, RenderMode::Flat, RenderMode::Nearest};

const char* paneLabel(RenderMode mode) {
    switch (mode) {
        case RenderMode::Lut: return "LUT";
        case RenderMode::Brdf: return "2D texture mapping (brdf)";
        case RenderMode::Ptm: return "PTM";
        case RenderMode::Flat: return "flat texture";
        case RenderMode::Nearest: return "nearest measured image";
    }
    return "";
}

// Which covered samples of a frame show a point of `quad` inside the material's sample mask.
void keepMasked(FrameSamples& samples, const Scene& scene, const SceneQuad& quad, const Mask& mask) {
    const PixelRays rays(scene);
    for (int j = 0; j < samples.height; ++j)
        for (int i = 0; i < samples.width; ++i) {
            std::uint8_t& covered = samples.covered[static_cast<std::size_t>(j) * samples.width + i];
            if (!covered) continue;
            const std::optional<std::array<double, 2>> uv = rays.quadTextureAt(quad, samples.pixelX(i), samples.pixelRow(j));
            if (!uv) {
                covered = 0;
                continue;
            }
            const double u = (*uv)[0] - std::floor((*uv)[0]), v = (*uv)[1] - std::floor((*uv)[1]);  // repeats
            const int tx = std::clamp(static_cast<int>(u * mask.width), 0, mask.width - 1);
            const int ty = std::clamp(static_cast<int>(v * mask.height), 0, mask.height - 1);
            covered = mask.inside[static_cast<std::size_t>(ty) * mask.width + tx] != 0;
        }
}

class Viewer {
public:
    Viewer(ViewerOptions options, ViewerInput input, Window& window)
        : m_options(std::move(options)), m_input(std::move(input)), m_window(window), m_orbit(Orbit::of(m_input.scene)) {}

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
    LevelCounts m_referenceGrey;     ///< over the sample mask, when the dataset has one
    std::optional<Mask> m_mask;      ///< the dataset's sample mask (single-quad views)
    std::string m_hovered;  ///< scene files: the material of the quad under the cursor

    Direction m_light = Direction::fromDegrees(45, 30);
    Orbit m_orbit;
    int m_split = 1;
    std::array<RenderMode, 3> m_paneModes{RenderMode::Lut, RenderMode::Lut, RenderMode::Nearest};
    bool m_interpolate = true;
    bool m_havePtm = false, m_haveImages = false;

    Geometry m_geometry = Geometry::Quad;
    std::unique_ptr<ShapeRenderer> m_shapes;  ///< made when a sphere or cylinder is first shown
    double m_pointLight = 0;  ///< > 0: a point light this far from the origin, in the light's direction
    bool m_flat = false;  ///< 2D mode: frontal, orthographic, 1:1 at zoom 1
    FlatView m_flatView;
    RenderMode m_compareMode = RenderMode::Brdf;  ///< image B of the wipe or lens
    PresentSettings m_present;
    PresentPass m_presentPass;
    bool m_draggingWipe = false;

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
        m_referenceGrey = countGreyLevels(m_bank->reference, m_mask ? *m_mask : fullMask(m_bank->reference.width, m_bank->reference.height));
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
    m_flat = m_options.projection.empty() ? m_options.camera.empty() && flatOffered() && m_bank->layers.size() == 1 && m_bank->layers[0].view.theta < M_PI / 180
                                          : m_options.projection == "2d";
    if (!m_options.compare.empty()) {
        Result<RenderMode> b = parseRenderMode(m_options.compareMode);
        if (!b) return Error{"--compare-" + b.error()};
        if (Status s = modeOffered(*b); !s) return s;
        m_compareMode = *b;
        m_present.compare = m_options.compare == "wipe" ? PresentSettings::Compare::Wipe : PresentSettings::Compare::Lens;
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
    for (auto [colour, framebuffer] : {std::pair{&m_compositeColour, &m_composite}, {&m_compositeColourB, &m_compositeB}}) {
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
        m_flatView.apply(scene, scene.quads[0], pane.width, pane.height, m_bank->reference.width, m_bank->reference.height);
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
            ShapeFrame frame{m_geometry == Geometry::Sphere ? Shape::Sphere : Shape::Cylinder, m_orbit.eye(), m_orbit.target,
                             {0, 0, 1}, m_input.scene.fovDegrees, {}};
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

// The rendered material's grey histogram against the bank's target for the light (at quad 0's
// centre), and the LUT there.
void Viewer::updatePlots() {
    if (!m_bank) return;
    // About 2^16 pixels of the frame, every stride-th across and down: plenty for 64 bins,
    // and a large window's frame is not read back whole each time the light moves.
    const Scene& scene = m_renderer->scene();
    const int stride = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(scene.width) * scene.height / 65536.0)));
    FrameSamples frame = m_renderer->sampleFrame(stride);
    if (m_mask) keepMasked(frame, scene, scene.quads[0], *m_mask);
    m_renderedHistogram.assign(kHistogramBins, 0.f);
    double total = 0;
    for (std::size_t i = 0; i < frame.covered.size(); ++i) {
        if (!frame.covered[i]) continue;
        const int grey = frame.rgb[3 * i] + frame.rgb[3 * i + 1] + frame.rgb[3 * i + 2];
        const int bin = std::min(kHistogramBins - 1, grey * kHistogramBins / 765);
        m_renderedHistogram[static_cast<std::size_t>(bin)] += 1;
        total += 1;
    }
    for (float& v : m_renderedHistogram) v = total > 0 ? static_cast<float>(v / total) : 0.f;

    const RelightFrame lut = m_renderer->centreFrame(0, lightVector());
    m_provenance = std::string("light ") + provenanceName(lut.lightProvenance) + ", view " + provenanceName(lut.viewProvenance);
    m_lutCurve.assign(lut.luts.begin(), lut.luts.begin() + m_bank->entries);  // region 0's, first channel
    m_targetHistogram.assign(kHistogramBins, 0.f);
    total = 0;
    auto add = [&](float v, double weight) {
        m_targetHistogram[static_cast<std::size_t>(std::min(kHistogramBins - 1, static_cast<int>(v * kHistogramBins)))] +=
            static_cast<float>(weight);
        total += weight;
    };
    if (m_bank->makesLuts()) {
        // The target's distribution from its quantile functions (first channel), each region
        // weighted by its sample texels.
        const LutBank::Blend& blend = m_bank->blend;
        const auto samples = static_cast<std::size_t>(blend.quantiles), channels = static_cast<std::size_t>(m_bank->channels());
        for (std::size_t i = 0; i < blend.mask.inside.size(); i += 16)  // every 16th texel: plenty for a plot
            if (blend.mask.inside[i]) {
                const std::size_t r = blend.labels.empty() ? 0 : blend.labels[i];
                for (std::size_t m = 0; m < samples; m += 8) add(lut.target.values[r * channels * samples + m], 1);
            }
    } else {
        for (std::size_t k = 0; k < m_referenceGrey.counts.size(); ++k)
            if (m_referenceGrey.counts[k])
                add(Lut::applyLut(lut.luts.data(), m_bank->entries, static_cast<float>(m_referenceGrey.valueOf(k))),
                    static_cast<double>(m_referenceGrey.counts[k]));
    }
    for (float& v : m_targetHistogram) v = total > 0 ? static_cast<float>(v / total) : 0.f;
}

Status Viewer::modeOffered(RenderMode m) const {
    if (m == RenderMode::Ptm && !m_havePtm) return Error{m_input.scene.file + ": mode ptm needs a bank baked with --ptm"};
    if (m == RenderMode::Nearest && !m_haveImages)
        return Error{m_input.scene.file + ": mode nearest needs the measured images (--images DATASET)"};
    return success();
}

bool Viewer::modeCombo(const char* label, RenderMode& mode) const {
    bool changed = false;
    if (ImGui::BeginCombo(label, renderModeName(mode))) {
        for (RenderMode m : kModes)
            if (ImGui::Selectable(renderModeName(m), m == mode, modeOffered(m) ? 0 : ImGuiSelectableFlags_Disabled)) {
                changed = m != mode;
                mode = m;
            }
        ImGui::EndCombo();
    }
    return changed;
}

// The ImGui panel; returns true when the scene must be drawn again.
bool Viewer::panel(int width, int height) {
    bool changed = false;
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - kPanelWidth, 0));
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, static_cast<float>(height)));
    ImGui::Begin("btflut", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("%.1f fps (%.2f ms/frame), scene %.2f ms", static_cast<double>(ImGui::GetIO().Framerate),
                1000.0 / static_cast<double>(std::max(ImGui::GetIO().Framerate, 1e-3f)), m_sceneMs);

    if (!m_message.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 120, 100, 255));
        ImGui::TextWrapped("%s", m_message.c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("dismiss")) m_message.clear();
    }
    if (ImGui::CollapsingHeader("File")) {
        ImGui::TextWrapped("%s", m_input.scene.file.c_str());
        ImGui::SetNextItemWidth(kPanelWidth - 80);
        const bool entered = ImGui::InputTextWithHint("##path", "bank, dataset or scene; or drop a file", m_pathField.data(),
                                                      m_pathField.size(), ImGuiInputTextFlags_EnterReturnsTrue);
        ImGui::SameLine();
        if ((ImGui::Button("Open") || entered) && m_pathField[0] != '\0') requestOpen(m_pathField.data());
        for (const std::string& recent : m_recent) {
            std::error_code ec;
            const bool present = fs::exists(recent, ec);
            const std::string label = present ? recent : recent + " (missing)";
            if (ImGui::Selectable(label.c_str(), recent == m_input.scene.file))
                present ? requestOpen(recent) : showMessage(recent + ": cannot open (no such file or folder any more)");
        }
    }
    if (ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) {
        const LutBank* shown = shownBank();
        changed |= hemisphereWidget("##hemisphere", m_light, shown ? shown->layers[0].nodes : std::vector<LightNode>{}, 200);
        if (!m_input.singleQuad)
            ImGui::TextDisabled("%s", m_hovered.empty() ? "dots: quad 0's material; hover a quad for its own"
                                                        : ("dots: '" + m_hovered + "', under the cursor").c_str());
        float theta = static_cast<float>(m_light.thetaDegrees()), phi = static_cast<float>(m_light.phiDegrees());
        bool edited = ImGui::InputFloat("theta", &theta, 1, 5, "%.1f");
        edited |= ImGui::InputFloat("phi", &phi, 1, 15, "%.1f");
        if (edited && std::isfinite(theta) && std::isfinite(phi)) {
            m_light = Direction::fromDegrees(std::clamp(static_cast<double>(theta), 0.0, 89.0),
                                             std::fmod(std::fmod(static_cast<double>(phi), 360.0) + 360.0, 360.0));
            changed = true;
        }
        ImGui::TextDisabled("drag the disk, or shift-drag the scene; F1: keys");
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextUnformatted("Panes");
        for (int n = 1; n <= 3; ++n) {
            ImGui::SameLine();
            const std::string label = std::to_string(n) + "##split";
            if (ImGui::RadioButton(label.c_str(), m_split == n)) {
                m_split = n;
                if (n > 1) m_paneModes = splitModes();
                resetCamera(width, height);
                changed = true;
            }
        }
        for (int p = 0; p < m_split; ++p)
            changed |= modeCombo(("mode##pane" + std::to_string(p)).c_str(), m_paneModes[static_cast<std::size_t>(p)]);
        if (flatOffered()) {
            ImGui::TextUnformatted("Projection");
            ImGui::SameLine();
            if (ImGui::RadioButton("2D (V)", m_flat) && !m_flat) m_flat = true, resetCamera(width, height), changed = true;
            ImGui::SameLine();
            if (ImGui::RadioButton("3D", !m_flat) && m_flat) m_flat = false, resetCamera(width, height), changed = true;
            if (m_flat) {
                ImGui::SameLine();
                if (ImGui::SmallButton("fit (F)")) fitFlat(width, height), changed = true;
                ImGui::SameLine();
                if (ImGui::SmallButton("1:1 (1)")) m_flatView.zoom = 1, changed = true;
                ImGui::SameLine();
                ImGui::Text("%.0f%%", 100 * m_flatView.zoom);
            }
        }
        int compare = static_cast<int>(m_present.compare);
        ImGui::TextUnformatted("Compare (C)");
        for (const auto& [value, name] : {std::pair{0, "off"}, {1, "wipe"}, {2, "lens"}}) {
            ImGui::SameLine();
            if (ImGui::RadioButton((std::string(name) + "##compare").c_str(), compare == value)) {
                m_present.compare = static_cast<PresentSettings::Compare>(value);
                changed = true;
            }
        }
        if (m_present.compare != PresentSettings::Compare::Off) {
            if (m_split > 1) ImGui::TextDisabled("compares in every pane: each pane's mode against B");
            changed |= modeCombo("B##compareMode", m_compareMode);
        }
        ImGui::SliderFloat("exposure", &m_present.exposure, -4, 4, "%+.1f stops");  // the present pass only
        ImGui::SliderFloat("gamma", &m_present.gamma, 0.5f, 3, "%.2f");
        ImGui::SameLine();
        if (ImGui::SmallButton("reset##tone")) m_present.exposure = 0, m_present.gamma = 1;
        if (m_input.singleQuad) {
            ImGui::TextUnformatted("Geometry (G)");
            for (const auto& [value, name] : {std::pair{Geometry::Quad, "quad"}, {Geometry::Sphere, "sphere"}, {Geometry::Cylinder, "cylinder"}}) {
                ImGui::SameLine();
                if (ImGui::RadioButton(name, m_geometry == value) && m_geometry != value) changed |= setGeometry(value, width, height);
            }
            if (curved()) {
                bool point = m_pointLight > 0;
                if (ImGui::Checkbox("point light (P)", &point)) m_pointLight = point ? 3 : 0, changed = true;
                if (point) {
                    float distance = static_cast<float>(m_pointLight);
                    ImGui::SameLine();
                    ImGui::SetNextItemWidth(140);
                    if (ImGui::SliderFloat("distance", &distance, 1.2f, 10, "%.1f")) m_pointLight = distance, changed = true;
                }
                ImGui::TextDisabled("mode lut, per fragment: each point's own light and view");
                if (!m_shapes->gridNote().empty()) {
                    ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 200, 90, 255));
                    ImGui::TextWrapped("%s", m_shapes->gridNote().c_str());
                    ImGui::PopStyleColor();
                }
            }
        }
        changed |= ImGui::Checkbox("interpolate LUTs between measured directions", &m_interpolate);
        if (ImGui::Button("Reset light and camera (R)")) {
            m_light = Direction::fromDegrees(45, 30);
            resetCamera(width, height);
            changed = true;
        }
        ImGui::SameLine();
        if (ImGui::Button("Screenshot (S)")) {
            m_status = "screenshot: next frame";
            m_screenshotRequested = true;
        }
        if (!m_status.empty()) ImGui::TextWrapped("%s", m_status.c_str());
    }
    if (m_bank && !curved() && ImGui::CollapsingHeader("Histogram and LUT", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextDisabled("bars: rendered material; line: the bank's target");
        histogramPlot("##histogram", m_renderedHistogram, m_targetHistogram, kPanelWidth - 20, 90);
        ImGui::PlotLines("##lut", m_lutCurve.data(), static_cast<int>(m_lutCurve.size()), 0, "LUT at the quad centre", 0, 1,
                         ImVec2(kPanelWidth - 20, 90));
    }
    if (const LutBank* bank = shownBank(); bank && bank != m_bank && ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) {
        // A scene's material under the cursor: what it is made of.
        ImGui::Text("'%s': %s", m_hovered.c_str(), m_input.scene.materials.at(m_hovered).bank.c_str());
        ImGui::Text("%d x %d reference, %s LUTs of %d entries", bank->reference.width, bank->reference.height,
                    colourName(bank->colour), bank->entries);
        std::size_t lights = 0;
        for (const ViewLayer& l : bank->layers) lights += l.nodes.size();
        ImGui::Text("%zu view layer(s), %zu light nodes", bank->layers.size(), lights);
    } else if (m_bank && ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) {
        std::size_t nodes = 0, modelled = 0;
        double maxTheta = 0;
        for (const ViewLayer& l : m_bank->layers)
            for (const LightNode& n : l.nodes) {
                if (n.modelled) {
                    ++modelled;
                    continue;
                }
                ++nodes;
                maxTheta = std::max(maxTheta, n.light.thetaDegrees());
            }
        ImGui::Text("%d x %d reference, %s LUTs of %d entries", m_bank->reference.width, m_bank->reference.height,
                    colourName(m_bank->colour), m_bank->entries);
        if (m_bank->makesLuts()) {
            const LutBank::Blend& blend = m_bank->blend;
            if (blend.predictor == LutBank::Blend::Predictor::Ptm)
                ImGui::Text("lut: the PTM relit, matched in %d region(s)", blend.regions);
            else
                ImGui::Text("lut: %zu references blended, matched in %d region(s)", blend.references.size(), blend.regions);
        }
        ImGui::Text("%zu view layer(s), %zu lights (theta <= %.0f)", m_bank->layers.size(), nodes, maxTheta);
        ImGui::Text("%.0f%% of light directions inside the measured", 100 * m_coverage);
        if (modelled > 0)
            ImGui::Text("hull (interpolated; outside: the model, %zu nodes)", modelled);
        else
            ImGui::Text("hull (interpolated; outside: clamped)");
        ImGui::Text("here: %s", m_provenance.c_str());
        ImGui::Text("PTM: %s, measured images: %s", m_havePtm ? "yes" : "no", m_haveImages ? "yes" : "no");
        if (m_input.modelParameters.is_object()) {
            ImGui::TextUnformatted("model parameters:");
            for (const auto& [key, value] : m_input.modelParameters.items())
                ImGui::BulletText("%s = %s", key.c_str(), jsonText(value, -1).c_str());
        }
    }
    ImGui::End();
    return changed;
}

// Mouse and keys over the scene: orbit, zoom, shift-drag the light, arrows, R, S.
bool Viewer::sceneInput(int width, int height) {
    const ImGuiIO& io = ImGui::GetIO();
    bool changed = false;
    const bool overScene = !io.WantCaptureMouse && io.MousePos.x < static_cast<float>(width - panelWidth());
    const float mouseX = io.MousePos.x, mouseY = static_cast<float>(height) - io.MousePos.y;  // GL: origin bottom left
    // The lens, the wipe line, exposure and gamma change only the present pass, which runs
    // every frame: moving them draws no pane again.
    if (m_present.compare == PresentSettings::Compare::Lens && overScene)
        m_present.lensX = mouseX, m_present.lensY = mouseY;  // the lens follows the cursor
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) m_draggingWipe = false;
    if (!m_input.singleQuad && overScene && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0 || m_hovered.empty()))
        m_hovered = materialAt(static_cast<int>(io.MousePos.x), static_cast<int>(io.MousePos.y), width, height);
    if (overScene && ImGui::IsMouseClicked(ImGuiMouseButton_Left) && m_present.compare == PresentSettings::Compare::Wipe &&
        std::abs(mouseX - m_present.wipeX) < 8)
        m_draggingWipe = true;  // grabbed the wipe line
    if (m_draggingWipe) {
        m_present.wipeX = std::clamp(mouseX, 0.f, static_cast<float>(width - panelWidth()));
    } else if (overScene) {
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0)) {
            const ImVec2 d = io.MouseDelta;
            if (io.KeyShift) {
                m_light.phi = std::fmod(m_light.phi - d.x * 0.01 + 2 * M_PI, 2 * M_PI);
                m_light.theta = std::clamp(m_light.theta + d.y * 0.01, 0.0, 89.0 * M_PI / 180);
            } else if (m_flat) {  // pan: the image follows the cursor
                m_flatView.panX -= d.x / m_flatView.zoom;
                m_flatView.panY += d.y / m_flatView.zoom;
            } else {
                m_orbit.azimuth -= d.x * 0.01;
                m_orbit.elevation = std::clamp(m_orbit.elevation + d.y * 0.01, 0.05, 1.55);
            }
            changed |= d.x != 0 || d.y != 0;
        }
        if (io.MouseWheel != 0 && io.KeyCtrl && m_present.compare == PresentSettings::Compare::Lens) {
            m_present.lensRadius = std::clamp(m_present.lensRadius * static_cast<float>(std::pow(1.1, io.MouseWheel)), 8.f, 2000.f);
        } else if (io.MouseWheel != 0 && m_flat) {  // zoom about the cursor, in the pane under it
            for (const Pane& p : panes(width, height))
                if (mouseX >= static_cast<float>(p.x) && mouseX < static_cast<float>(p.x + p.width))
                    m_flatView.zoomAbout(std::pow(1.25, io.MouseWheel), mouseX - p.x, mouseY - p.y, p.width, p.height);
            changed = true;
        } else if (io.MouseWheel != 0) {
            m_orbit.distance = std::clamp(m_orbit.distance * std::pow(0.9, io.MouseWheel), 0.2, 100.0);
            changed = true;
        }
    }
    if (!io.WantCaptureKeyboard) {
        const double step = M_PI / 180;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow))) m_light.phi = std::fmod(m_light.phi + 2 * M_PI - step, 2 * M_PI), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow))) m_light.phi = std::fmod(m_light.phi + step, 2 * M_PI), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_UpArrow))) m_light.theta = std::max(0.0, m_light.theta - step), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_DownArrow))) m_light.theta = std::min(89 * step, m_light.theta + step), changed = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_R)) {
            m_light = Direction::fromDegrees(45, 30);
            resetCamera(width, height);
            changed = true;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_S) || ImGui::IsKeyPressed(GLFW_KEY_F12)) m_screenshotRequested = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_V) && flatOffered()) {
            m_flat = !m_flat;
            resetCamera(width, height);
            changed = true;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F) && m_flat) fitFlat(width, height), changed = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_G) && m_input.singleQuad)
            changed |= setGeometry(static_cast<Geometry>((static_cast<int>(m_geometry) + 1) % 3), width, height);
        if (ImGui::IsKeyPressed(GLFW_KEY_P) && curved()) m_pointLight = m_pointLight > 0 ? 0 : 3, changed = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_1) && m_flat) m_flatView.zoom = 1, changed = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_C)) {
            m_present.compare = static_cast<PresentSettings::Compare>((static_cast<int>(m_present.compare) + 1) % 3);
            changed = true;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_TAB)) {
            m_panelVisible = !m_panelVisible;
            changed = true;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F1) || (ImGui::IsKeyPressed(GLFW_KEY_SLASH) && io.KeyShift)) {
            m_helpVisible = !m_helpVisible;
            changed = true;
        }
    }
    return changed;
}

// F1 or ?: every key and mouse action, in a window over the scene.
void Viewer::keyHelp() {
    if (!m_helpVisible) return;
    static const char* const kKeys[][2] = {
        {"drag", "3D: orbit the camera; 2D: pan"},
        {"shift + drag", "move the light"},
        {"wheel", "zoom (2D: about the cursor)"},
        {"V", "2D (frontal, orthographic) or 3D"},
        {"F, 1", "2D: fit the image to the pane; one texel per pixel"},
        {"G", "geometry: quad, sphere, cylinder"},
        {"P", "sphere and cylinder: point light or directional"},
        {"C", "compare: off, wipe (drag the line), lens (follows the cursor; ctrl + wheel: size)"},
        {"arrows", "light: left/right 1 degree in phi, up/down 1 degree in theta"},
        {"R", "reset the light and the camera"},
        {"S, F12", "screenshot (--screenshot, or btflut-screenshot-PID-N.png)"},
        {"Tab", "hide or show the panel"},
        {"F1, ?", "this help"},
    };
    ImGui::SetNextWindowPos(ImVec2(20, 40), ImGuiCond_Always);
    ImGui::Begin("Keys", &m_helpVisible, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    for (const auto& [key, action] : kKeys) {
        ImGui::TextUnformatted(key);
        ImGui::SameLine(120);
        ImGui::TextUnformatted(action);
    }
    ImGui::End();
}

void Viewer::fitFlat(int width, int height) {
    const Pane pane = panes(width, height)[0];
    m_flatView.fit(pane.width, pane.height, m_bank->reference.width, m_bank->reference.height);
}

// The frames' times after the first (which compiles shaders and uploads textures).
void Viewer::reportTiming() const {
    if (m_frameMs.size() < 2) return;
    std::vector<double> ms(m_frameMs.begin() + 1, m_frameMs.end());
    std::sort(ms.begin(), ms.end());
    int width = 0, height = 0;
    glfwGetFramebufferSize(m_window.handle(), &width, &height);
    std::printf("view timing: %zu frames at %dx%d (%s, %s%s): median %.2f ms, 90th percentile %.2f ms, slowest %.2f ms\n",
                ms.size(), width, height, m_flat ? "2D" : "3D", renderModeName(m_paneModes[0]),
                m_options.lightSweep ? ", the light moving every frame" : "", ms[ms.size() / 2], ms[ms.size() * 9 / 10],
                ms.back());
}

void Viewer::compareOverlay(int height) const {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const auto h = static_cast<float>(height);
    const ImU32 white = IM_COL32(255, 255, 255, 220);
    const std::string a = std::string("A: ") + renderModeName(m_paneModes[0]), b = std::string("B: ") + renderModeName(m_compareMode);
    if (m_present.compare == PresentSettings::Compare::Wipe) {
        draw->AddLine(ImVec2(m_present.wipeX, 0), ImVec2(m_present.wipeX, h), white, 2);
        draw->AddText(ImVec2(m_present.wipeX - 8 - ImGui::CalcTextSize(a.c_str()).x, h - 24), white, a.c_str());
        draw->AddText(ImVec2(m_present.wipeX + 8, h - 24), white, b.c_str());
    } else if (m_present.compare == PresentSettings::Compare::Lens) {
        draw->AddCircle(ImVec2(m_present.lensX, h - m_present.lensY), m_present.lensRadius, white, 64, 2);
        draw->AddText(ImVec2(m_present.lensX - m_present.lensRadius, h - m_present.lensY + m_present.lensRadius + 4), white,
                      (b + " in the lens, " + a + " outside").c_str());
    }
}

// The scene's camera; around a single quad, moved back until the quad fits one pane. In 2D
// the image fits the pane.
std::string Viewer::materialAt(int x, int row, int width, int height) const {
    for (const Pane& pane : panes(width, height)) {
        if (x < pane.x || x >= pane.x + pane.width) continue;
        Scene scene = m_input.scene;
        paneCamera(pane, scene);
        scene.width = pane.width, scene.height = pane.height;
        const PixelRays rays(scene);
        // Of the quads this pixel's ray crosses in front of the camera, the nearest.
        std::string found;
        double nearest = INFINITY;
        for (const SceneQuad& quad : scene.quads) {
            const std::optional<PixelRays::QuadHit> hit = rays.hit(quad, x - pane.x, row);
            if (!hit || hit->distance < 0 || hit->distance >= nearest) continue;
            const auto [u, v] = hit->uv;
            if (u < 0 || u > quad.uvScale || v < 0 || v > quad.uvScale) continue;
            nearest = hit->distance, found = quad.material;
        }
        return found;
    }
    return {};
}

bool Viewer::setGeometry(Geometry geometry, int width, int height) {
    if (geometry != Geometry::Quad && !m_shapes) {
        Result<std::unique_ptr<ShapeRenderer>> shapes =
            m_bank ? ShapeRenderer::create(m_input.scene.materials.at(m_input.scene.quads[0].material).bank)
                   : Result<std::unique_ptr<ShapeRenderer>>(Error{"a scene file has no one material"});
        if (!shapes) {
            m_message = "sphere and cylinder: " + shapes.error();
            return false;
        }
        m_shapes = std::move(*shapes);
    }
    m_geometry = geometry;
    if (curved()) m_flat = false;
    resetCamera(width, height);
    return true;
}

void Viewer::resetCamera(int width, int height) {
    if (m_flat && width > 0 && height > 0) fitFlat(width, height);
    m_orbit = Orbit::of(m_input.scene);
    if (!m_input.singleQuad || width <= 0 || height <= 0) return;
    const Pane pane = panes(width, height)[0];
    const double paneAspect = static_cast<double>(pane.width) / pane.height;
    double halfWidth = m_input.scene.quads[0].width / 2, halfHeight = m_input.scene.quads[0].height / 2;
    if (curved()) {  // the shape at the origin, seen a little from above
        m_orbit.target = {0, 0, 0};
        m_orbit.elevation = 0.35;
        m_orbit.distance = 0;
        halfWidth = halfHeight = m_geometry == Geometry::Sphere ? 1.2 : 1.6;
    }
    const double tanHalfFov = std::tan(m_input.scene.fovDegrees / 2 * M_PI / 180);
    m_orbit.distance = std::max(m_orbit.distance, 1.15 * std::max(halfHeight, halfWidth / paneAspect) / tanHalfFov);
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
    if (!m_input.temporaryBank.empty()) {  // the session's bank goes when the viewer does: keep a copy
        const fs::path kept = dir / "material.btflut";
        if (!fs::exists(kept)) {
            Result<Bytes> bytes = readFile(m_input.temporaryBank);
            if (!bytes) return Error{bytes.error()};
            if (Status s = writeFileAtomically(kept.string(), *bytes); !s) return s;
        }
        for (auto& [name, material] : scene.materials)
            if (material.bank == m_input.temporaryBank) material.bank = kept.string();
    }
    const std::string sceneFile = std::string(stem) + ".scene.json";
    if (Status s = writeFileAtomically((dir / sceneFile).string(), sceneToJson(scene, dir.string())); !s) return s;  // paths relative to it
    json state{{"frame", frame},
                     {"light", {{"theta", m_light.thetaDegrees()}, {"phi", m_light.phiDegrees()}}},
                     {"mode", renderModeName(pane.mode)},
                     {"projection", m_flat ? "2d" : "3d"},
                     {"input", m_input.scene.file},
                     {"geometry", m_geometry == Geometry::Quad ? "quad" : m_geometry == Geometry::Sphere ? "sphere" : "cylinder"},
                     {"point_light", m_pointLight},
                     {"grid_note", m_shapes ? m_shapes->gridNote() : ""},
                     {"hovered_material", m_hovered},
                     {"help_visible", m_helpVisible},
                     {"message", m_message},
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
        const double left = pane.width / 2.0 - (camera.target.x - scene.quads[0].center.x) * texelsPerWorld * m_flatView.zoom -
                            m_bank->reference.width * m_flatView.zoom / 2;
        const double top = pane.height / 2.0 + (camera.target.y - scene.quads[0].center.y) * texelsPerWorld * m_flatView.zoom -
                           m_bank->reference.height * m_flatView.zoom / 2;
        state["image_rect"] = {pane.x + left, height - pane.y - pane.height + top, m_bank->reference.width * m_flatView.zoom,
                               m_bank->reference.height * m_flatView.zoom};
    }
    return writeFileAtomically((dir / (std::string(stem) + ".json")).string(), jsonText(state));
}

// The viewer that GLFW's drop callback hands paths to (one window, one viewer at a time).
Viewer* g_dropTarget = nullptr;

void onDrop(GLFWwindow*, int count, const char** paths) {
    if (g_dropTarget && count > 0) g_dropTarget->requestOpen(paths[0]);  // the first of several
}

Status Viewer::run(int& frame) {
    GLFWwindow* window = m_window.handle();
    g_dropTarget = this;
    glfwSetDropCallback(window, onDrop);
    if (!m_started) {
        m_started = true;
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        resetCamera(width, height);
        if (m_flat && !m_options.zoom.empty() && m_options.zoom != "fit") m_flatView.zoom = std::stod(m_options.zoom);  // validated
        m_present.wipeX = static_cast<float>(width - panelWidth()) / 2;
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
            if (std::sscanf(m_options.injectCursor.c_str(), "%f,%f", &x, &y) == 2) ImGui::GetIO().MousePos = ImVec2(x, y);
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
            ImGui::GetForegroundDrawList()->AddText(ImVec2(static_cast<float>(width) - 190, 8), IM_COL32(200, 200, 200, 255),
                                                    "Tab: panel   F1: keys");
        keyHelp();
        compareOverlay(height);
        const std::vector<Pane> all = panes(width, height);
        for (const Pane& p : all)  // labels over the panes
            if (all.size() > 1)
                ImGui::GetForegroundDrawList()->AddText(ImVec2(static_cast<float>(p.x) + 8, 8), IM_COL32(255, 255, 255, 255),
                                                        paneLabel(p.mode));
        ImGui::Render();
        PresentSettings present = m_present;
        if (curved()) present.compare = PresentSettings::Compare::Off;  // the shapes draw mode lut only
        if (Status s = m_presentPass.draw({m_composite.id(), m_compositeColour.id()}, {m_compositeB.id(), m_compositeColourB.id()},
                                          present, width, height);
            !s)
            return s;
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (scripted && !m_options.screenshotDir.empty())
            if (Status s = saveScriptedFrame(frame, width, height); !s) return s;
        const bool last = scripted && frame + 1 == m_options.frames;
        if (m_screenshotRequested || (last && !m_options.screenshot.empty())) {
            const std::string path = !m_options.screenshot.empty() ? m_options.screenshot
                                                                   : "btflut-screenshot-" + std::to_string(::getpid()) + "-" +
                                                                         std::to_string(frame) + ".png";
            if (Status s = screenshot(path, width, height); !s) return s;
            m_screenshotRequested = false;
            idleFrames = 0;  // show the status line
        }
        glfwSwapBuffers(window);
        if (m_options.timing) {
            gl.Finish();  // the frame's time is the whole of its work, the GPU's included
            m_frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count());
        }
    }
    if (m_options.timing && m_openRequest.empty()) reportTiming();
    return success();
}

}  // namespace

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
            return Error{"--zoom '" + options.zoom + "': expected fit, or pixels per texel from 1/64 to 64 (1: one texel per pixel)"};
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
        if ((n != 2 && n != 3) || !std::isfinite(azimuth) || !std::isfinite(elevation) || elevation < 3 || elevation > 89 ||
            !std::isfinite(distance) || distance <= 0)
            return Error{"--camera '" + options.camera + "': expected AZIMUTH,ELEVATION[,DISTANCE] in degrees, elevation "
                         "3 to 89, distance > 0"};
    }
    // The window first: without a display there is nothing to do, and nothing to bake.
    Result<std::unique_ptr<Window>> window = Window::create(options.width, options.height, "btflut view", options.vsync);
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
            next.light = std::to_string(viewer->light().thetaDegrees()) + "," + std::to_string(viewer->light().phiDegrees());
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
