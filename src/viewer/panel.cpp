// The Dear ImGui panel beside the scene: file, light, view, the histogram and LUT plots,
// the material; the key help and the compare overlay (app.h).

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>

#include "core/histogram/lut.h"
#include "core/io/json_text.h"
#include "viewer/app.h"
#include "viewer/widgets.h"

namespace btflut {

namespace {

namespace fs = std::filesystem;

const RenderMode kModes[] = {RenderMode::Lut, RenderMode::Brdf, RenderMode::Ptm, RenderMode::Flat, RenderMode::Nearest};

// Which covered samples of a frame show a point of `quad` inside the material's sample mask.
void keepMasked(FrameSamples& samples, const Scene& scene, const SceneQuad& quad, const Mask& mask) {
    const PixelRays rays(scene);
    for (int j = 0; j < samples.height; ++j)
        for (int i = 0; i < samples.width; ++i) {
            std::uint8_t& covered = samples.covered[static_cast<std::size_t>(j) * samples.width + i];
            if (!covered) continue;
            const std::optional<std::array<double, 2>> uv =
                rays.quadTextureAt(quad, samples.pixelX(i), samples.pixelRow(j));
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

}  // namespace

// The rendered material's grey histogram against the bank's target for the light (at quad 0's
// centre), and the LUT there.
void Viewer::updatePlots() {
    if (!m_bank) return;
    // About 2^16 pixels of the frame, every stride-th across and down: plenty for 64 bins,
    // and a large window's frame is not read back whole each time the light moves.
    const Scene& scene = m_renderer->scene();
    const int stride =
        std::max(1, static_cast<int>(std::sqrt(static_cast<double>(scene.width) * scene.height / 65536.0)));
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
    m_provenance =
        std::string("light ") + provenanceName(lut.lightProvenance) + ", view " + provenanceName(lut.viewProvenance);
    m_lutCurve.assign(lut.luts.begin(), lut.luts.begin() + m_bank->entries);  // region 0's, first channel
    m_targetHistogram.assign(kHistogramBins, 0.f);
    total = 0;
    auto add = [&](float v, double weight) {
        m_targetHistogram[static_cast<std::size_t>(
            std::min(kHistogramBins - 1, static_cast<int>(v * kHistogramBins)))] += static_cast<float>(weight);
        total += weight;
    };
    if (m_bank->makesLuts()) {
        // The target's distribution from its quantile functions (first channel), each region
        // weighted by its sample texels.
        const LutBank::Prediction& prediction = m_bank->prediction;
        const auto samples = static_cast<std::size_t>(prediction.quantiles),
                   channels = static_cast<std::size_t>(m_bank->channels());
        for (std::size_t i = 0; i < prediction.mask.inside.size(); i += 16)  // every 16th texel: plenty for a plot
            if (prediction.mask.inside[i]) {
                const std::size_t r = prediction.labels.empty() ? 0 : prediction.labels[i];
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
    if (m == RenderMode::Ptm && !m_havePtm)
        return Error{m_input.scene.file + ": mode ptm needs a bank baked with --ptm"};
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

// "File": the scene's file, a path to open, the recent ones.
void Viewer::filePanel() {
    if (!ImGui::CollapsingHeader("File")) return;
    ImGui::TextWrapped("%s", m_input.scene.file.c_str());
    ImGui::SetNextItemWidth(kPanelWidth - 80);
    const bool entered =
        ImGui::InputTextWithHint("##path", "bank, dataset or scene; or drop a file", m_pathField.data(),
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

// "Light": the hemisphere and the light's angles; true when the light moved.
bool Viewer::lightPanel() {
    if (!ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen)) return false;
    bool changed = false;
    const LutBank* shown = shownBank();
    changed |=
        hemisphereWidget("##hemisphere", m_light, shown ? shown->layers[0].nodes : std::vector<LightNode>{}, 200);
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
    return changed;
}

// "View": panes, projection, compare, tone, geometry, reset and screenshot; true when the
// scene must be drawn again.
bool Viewer::viewPanel(int width, int height) {
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return false;
    bool changed = false;
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
        for (const auto& [value, name] :
             {std::pair{Geometry::Quad, "quad"}, {Geometry::Sphere, "sphere"}, {Geometry::Cylinder, "cylinder"}}) {
            ImGui::SameLine();
            if (ImGui::RadioButton(name, m_geometry == value) && m_geometry != value)
                changed |= setGeometry(value, width, height);
        }
        if (curved()) {
            bool point = m_pointLight > 0;
            if (ImGui::Checkbox("point light (P)", &point)) m_pointLight = point ? 3 : 0, changed = true;
            if (point) {
                float distance = static_cast<float>(m_pointLight);
                ImGui::SameLine();
                ImGui::SetNextItemWidth(140);
                if (ImGui::SliderFloat("distance", &distance, 1.2f, 10, "%.1f"))
                    m_pointLight = distance, changed = true;
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
    return changed;
}

// "Material": the bank shown (or a scene's material under the cursor), its lights and hull.
void Viewer::materialPanel() {
    if (const LutBank* bank = shownBank();
        bank && bank != m_bank && ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) {
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
            const LutBank::Prediction& prediction = m_bank->prediction;
            ImGui::Text("lut: %s, matched (%.2f) in %d region(s)", m_bank->predictor().description().c_str(),
                        static_cast<double>(prediction.match), prediction.regions);
        }
        ImGui::Text("%zu view layer(s), %zu lights (theta <= %.0f)", m_bank->layers.size(), nodes, maxTheta);
        ImGui::Text("%.0f%% of light directions inside the measured", 100 * m_coverage);
        if (modelled > 0)
            ImGui::Text("hull (interpolated; outside: the model, %zu nodes)", modelled);
        else
            ImGui::Text("hull (interpolated; outside: clamped)");
        ImGui::Text("here: %s", m_provenance.c_str());
        if (m_provenance.starts_with("light clamped"))  // the words relight and info use
            ImGui::TextWrapped(
                "The light is beyond the measured lights: clamped to their edge, which can show wrong shadows "
                "far from it. `bake --fill model` fills such lights from the fitted rough-surface model.");
        ImGui::Text("PTM: %s, measured images: %s", m_havePtm ? "yes" : "no", m_haveImages ? "yes" : "no");
        if (m_input.modelParameters.is_object()) {
            ImGui::TextUnformatted("model parameters:");
            for (const auto& [key, value] : m_input.modelParameters.items())
                ImGui::BulletText("%s = %s", key.c_str(), jsonText(value, -1).c_str());
        }
    }
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
    filePanel();
    changed |= lightPanel();
    changed |= viewPanel(width, height);
    if (m_bank && !curved() && ImGui::CollapsingHeader("Histogram and LUT", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextDisabled("bars: rendered material; line: the bank's target");
        histogramPlot("##histogram", m_renderedHistogram, m_targetHistogram, kPanelWidth - 20, 90);
        ImGui::PlotLines("##lut", m_lutCurve.data(), static_cast<int>(m_lutCurve.size()), 0, "LUT at the quad centre",
                         0, 1, ImVec2(kPanelWidth - 20, 90));
    }
    materialPanel();
    ImGui::End();
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

void Viewer::compareOverlay(int height) const {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const auto h = static_cast<float>(height);
    const ImU32 white = IM_COL32(255, 255, 255, 220);
    const std::string a = std::string("A: ") + renderModeName(m_paneModes[0]),
                      b = std::string("B: ") + renderModeName(m_compareMode);
    if (m_present.compare == PresentSettings::Compare::Wipe) {
        draw->AddLine(ImVec2(m_present.wipeX, 0), ImVec2(m_present.wipeX, h), white, 2);
        draw->AddText(ImVec2(m_present.wipeX - 8 - ImGui::CalcTextSize(a.c_str()).x, h - 24), white, a.c_str());
        draw->AddText(ImVec2(m_present.wipeX + 8, h - 24), white, b.c_str());
    } else if (m_present.compare == PresentSettings::Compare::Lens) {
        draw->AddCircle(ImVec2(m_present.lensX, h - m_present.lensY), m_present.lensRadius, white, 64, 2);
        draw->AddText(ImVec2(m_present.lensX - m_present.lensRadius, h - m_present.lensY + m_present.lensRadius + 4),
                      white, (b + " in the lens, " + a + " outside").c_str());
    }
}

}  // namespace btflut
