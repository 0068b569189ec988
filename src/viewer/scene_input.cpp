// The mouse and keys over the scene (app.h): orbit, pan and zoom, the light, the compare
// line and lens, geometry and 2D/3D switches; the camera reset and the hovered material.

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "viewer/app.h"

namespace btflut {

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
    if (overScene && ImGui::IsMouseClicked(ImGuiMouseButton_Left) &&
        m_present.compare == PresentSettings::Compare::Wipe && std::abs(mouseX - m_present.wipeX) < 8)
        m_draggingWipe = true;  // grabbed the wipe line
    if (m_draggingWipe) {
        m_wipeAt = std::clamp(mouseX / static_cast<float>(std::max(1, width - panelWidth())), 0.f, 1.f);
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
            m_present.lensRadius =
                std::clamp(m_present.lensRadius * static_cast<float>(std::pow(1.1, io.MouseWheel)), 8.f, 2000.f);
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
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_LeftArrow)))
            m_light.phi = std::fmod(m_light.phi + 2 * M_PI - step, 2 * M_PI), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_RightArrow)))
            m_light.phi = std::fmod(m_light.phi + step, 2 * M_PI), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_UpArrow)))
            m_light.theta = std::max(0.0, m_light.theta - step), changed = true;
        if (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_DownArrow)))
            m_light.theta = std::min(89 * step, m_light.theta + step), changed = true;
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

void Viewer::fitFlat(int width, int height) {
    const Pane pane = panes(width, height)[0];
    m_flatView.fit(pane.width, pane.height, m_bank->reference.width, m_bank->reference.height);
}

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

// The scene's camera; around a single quad, moved back until the quad fits one pane. In 2D
// the image fits the pane.
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

}  // namespace btflut
