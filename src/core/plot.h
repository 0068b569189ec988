#pragma once
// Histogram figures in the paper's layout (Figs. 7-9): one small panel per position, top to
// bottom, one column per file, drawn into an RGB image (no GL, no plotting library; text
// from stb_easy_font).
//
//   Image fig = plotHistograms({{"concrete", rows}, {"model", simulated}});
//   savePng(fig, "fig.png");
//
// Each panel is scaled to its largest bin (printed in its top right corner), as in the
// paper; the x axis runs over grey values 0..1. Rows named c2-4,
// c2-6, c2-8 (curet-c2) are marked L (frontal to the lamp), S (specular), C (frontal to the
// camera).

#include <string>
#include <vector>

#include "core/histogram.h"
#include "core/image.h"

namespace btflut {

struct PlotColumn {
    std::string title;
    std::vector<HistogramRow> rows;
};

/// The figure; columns may hold different numbers of rows and bins. At least one column
/// with one row.
Image plotHistograms(const std::vector<PlotColumn>& columns);

/// A labelled image in a contact sheet.
struct SheetCell {
    std::string label;
    Image image;  ///< grey or RGB
};

/// Rows of images side by side, each scaled (box filter) to `cellWidth` pixels wide, its
/// label above it.
Image contactSheet(const std::vector<std::vector<SheetCell>>& rows, int cellWidth);

}  // namespace btflut
