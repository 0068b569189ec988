#pragma once
// Charts of eval's figures, drawn into an RGB image (core/image/canvas.h): panels of labelled
// points (error against cost, with the Pareto front) and of lines (error against the light's
// theta). A figure that is NaN has no point.
//
//   ChartPanel p{.title = "PSNR against bytes per texel", .xLabel = "bytes/texel", .yLabel = "dB",
//                .logX = true, .pareto = Better::Higher};
//   p.series.push_back({"lut auto", {9.0}, {31.2}});
//   savePng(drawCharts({p}, 1), "tradeoff.png");

#include <string>
#include <vector>

#include "core/image/image.h"

namespace btflut {

enum class Better { None, Higher, Lower };

struct ChartSeries {
    std::string label;
    std::vector<double> x, y;  ///< the same length; NaN: no point
};

struct ChartPanel {
    std::string title, xLabel, yLabel;
    bool logX = false;             ///< a logarithmic x axis (where every x > 0)
    bool lines = false;            ///< each series a line through its points, a legend; else labelled points
    Better pareto = Better::None;  ///< points: draw the front (smaller x is better; y better as said)
    std::vector<ChartSeries> series;
};

/// The indices of the points on the Pareto front of (cost, value): no other point costs at
/// most as much and is at least as good, one of them strictly. NaN points are never on it.
/// In order of cost.
std::vector<std::size_t> paretoFront(const std::vector<double>& cost, const std::vector<double>& value, Better better);

/// The numbers an axis over `values` (NaN ignored) is labelled with, in order: ticks at 1, 2, 5
/// per decade on a log axis (every digit where that gives fewer than three), at a round step
/// on a linear one, each with the decimals its step needs, so no two read the same.
std::vector<std::string> axisTickLabels(const std::vector<double>& values, bool log);

/// The panels in `columns` columns, row by row. A point's label goes beside it where it covers
/// no other label or point (moved a line at a time, with a leader line, where it must).
Image drawCharts(const std::vector<ChartPanel>& panels, int columns);

}  // namespace btflut
