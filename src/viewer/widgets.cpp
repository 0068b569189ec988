#include "viewer/widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace btflut {

namespace {

// Equal-area disk point of a direction and back (as core/direction/direction.h's toDisk).
ImVec2 diskOf(Direction d) {
    const DiskPoint p = toDisk(d);
    return {static_cast<float>(p.x), static_cast<float>(p.y)};
}

Direction directionOfDisk(double x, double y) {
    const double r = std::min(std::hypot(x, y), 0.9999);  // the horizon itself is never lit
    const double theta = 2 * std::asin(r / std::sqrt(2.0));
    double phi = std::atan2(y, x);
    if (phi < 0) phi += 2 * M_PI;
    return Direction{theta, phi};
}

}  // namespace

bool hemisphereWidget(const char* id, Direction& light, const std::vector<LightNode>& nodes, float size) {
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(id, ImVec2(size, size));
    const float radius = size * 0.5f - 4;
    const ImVec2 centre(origin.x + size * 0.5f, origin.y + size * 0.5f);
    // Disk x to the right, y up (screen y down).
    auto toScreen = [&](ImVec2 p) { return ImVec2(centre.x + p.x * radius, centre.y - p.y * radius); };
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddCircleFilled(centre, radius, IM_COL32(40, 44, 52, 255), 64);
    for (double theta : {30.0, 60.0})
        draw->AddCircle(centre, radius * diskOf(Direction::fromDegrees(theta, 0)).x, IM_COL32(80, 86, 96, 255), 64);
    draw->AddCircle(centre, radius, IM_COL32(140, 146, 156, 255), 64, 1.5f);
    draw->AddLine(ImVec2(centre.x - radius, centre.y), ImVec2(centre.x + radius, centre.y), IM_COL32(80, 86, 96, 255));
    draw->AddLine(ImVec2(centre.x, centre.y - radius), ImVec2(centre.x, centre.y + radius), IM_COL32(80, 86, 96, 255));
    for (const LightNode& n : nodes) {  // measured: filled blue; filled from the model: hollow grey
        if (n.modelled)
            draw->AddCircle(toScreen(diskOf(n.light)), 2.5f, IM_COL32(150, 150, 150, 255));
        else
            draw->AddCircleFilled(toScreen(diskOf(n.light)), 2.5f, IM_COL32(120, 180, 255, 255));
    }
    const ImVec2 marker = toScreen(diskOf(light));
    draw->AddCircleFilled(marker, 6, IM_COL32(255, 210, 60, 255));
    draw->AddCircle(marker, 6, IM_COL32(20, 20, 20, 255));

    if (ImGui::IsItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        const Direction moved = directionOfDisk((mouse.x - centre.x) / radius, (centre.y - mouse.y) / radius);
        if (std::abs(moved.theta - light.theta) > 1e-9 || std::abs(moved.phi - light.phi) > 1e-9) {
            light = moved;
            return true;
        }
    }
    return false;
}

void histogramPlot(const char* id, const std::vector<float>& measured, const std::vector<float>& expected, float width,
                   float height) {
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton(id, ImVec2(width, height));
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(30, 32, 38, 255));
    float top = 1e-6f;
    for (float v : measured) top = std::max(top, v);
    for (float v : expected) top = std::max(top, v);
    const std::size_t bins = std::max(measured.size(), expected.size());
    if (bins == 0) return;
    const float binWidth = width / static_cast<float>(bins);
    auto y = [&](float v) { return origin.y + height - v / top * (height - 2); };
    for (std::size_t b = 0; b < measured.size(); ++b) {
        const float x = origin.x + static_cast<float>(b) * binWidth;
        draw->AddRectFilled(ImVec2(x, y(measured[b])), ImVec2(x + binWidth - 1, origin.y + height),
                            IM_COL32(110, 170, 240, 255));
    }
    for (std::size_t b = 1; b < expected.size(); ++b) {
        const float x0 = origin.x + (static_cast<float>(b) - 0.5f) * binWidth;
        draw->AddLine(ImVec2(x0, y(expected[b - 1])), ImVec2(x0 + binWidth, y(expected[b])),
                      IM_COL32(255, 170, 60, 255), 2);
    }
}

}  // namespace btflut
