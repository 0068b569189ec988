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

#include "core/histogram/histogram.h"
#include "core/image/image.h"

namespace btflut {

struct PlotColumn {
    std::string title;
    std::vector<HistogramRow> rows;
};

struct PlotStyle {
    enum class Layout {
        Columns,       ///< the paper's: a panel per column, each scaled to its largest bin
        Overlay,       ///< one panel per position: the first column as bars, the others as outlines
        AgainstFirst,  ///< a panel per later column: the first column as bars, the column as an outline
    };
    Layout layout = Layout::Columns;
    int panelWidth = 256, panelHeight = 60;
};

/// The figure; columns may hold different numbers of rows and bins. At least one column
/// with one row. Overlay and AgainstFirst scale a position's panels to its largest bin over
/// all columns and label that common y axis (fraction of texels: 0, half, the top), with a
/// legend above. Row labels and titles are never clipped: the left margin fits the longest
/// label, and a title wider than its panel is shortened with "..".
Image plotHistograms(const std::vector<PlotColumn>& columns, const PlotStyle& style = {});

/// A labelled image in a contact sheet.
struct SheetCell {
    std::string label;
    Image image;  ///< grey or RGB
};

/// Rows of images side by side, each scaled (box filter) to `cellWidth` pixels wide, its
/// label above it.
Image contactSheet(const std::vector<std::vector<SheetCell>>& rows, int cellWidth);

}  // namespace btflut
