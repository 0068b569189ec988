#pragma once
// Dear ImGui widgets of the viewer.

#include <string>
#include <vector>

#include "core/bank/lut_bank.h"

namespace btflut {

/// The hemisphere of light directions as a disk (Lambert equal-area, like the bank's disk:
/// frontal at the centre, the horizon on the rim), with `nodes` as dots (modelled ones hollow) and the light as a
/// marker. Clicking or dragging moves the light; returns true when it changed.
bool hemisphereWidget(const char* id, Direction& light, const std::vector<LightNode>& nodes, float size);

/// Two distributions over the same bins: `measured` as bars, `expected` as a line.
void histogramPlot(const char* id, const std::vector<float>& measured, const std::vector<float>& expected, float width,
                   float height);

}  // namespace btflut
