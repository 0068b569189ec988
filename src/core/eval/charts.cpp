#include "core/eval/charts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/check.h"
#include "core/image/canvas.h"

namespace btflut {

namespace {

constexpr int kPanelW = 420, kPanelH = 300;                      // the plot area
constexpr int kLeft = 76, kRight = 24, kTop = 40, kBottom = 52;  // around it: ticks, labels, title
constexpr int kLegendW = 300;  // line panels: the legend, right of the plot (names of ~27 characters whole)
constexpr int kCellW = kLeft + kPanelW + kRight, kCellH = kTop + kPanelH + kBottom;

// A tick's number with as many decimals as the ticks' spacing needs, so that neighbours differ
// (0.1455 and 0.146, not 0.146 twice); a logarithmic axis's (spacing 0) with three digits.
std::string tickText(double v, double spacing) {
    char buf[32];
    if (spacing > 0) {
        const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(spacing) + 1e-9)), 0, 8);
        std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    } else {
        std::snprintf(buf, sizeof buf, "%.3g", v);
    }
    return buf;
}

double spacingOf(const std::vector<double>& ticks, bool log) {
    return log || ticks.size() < 2 ? 0 : ticks[1] - ticks[0];
}

// An axis: [lo, hi] padded, linear or logarithmic, onto [0, length] pixels.
struct Axis {
    double lo = 0, hi = 1;
    bool log = false;
    static Axis of(const std::vector<double>& values, bool log) {
        Axis a;
        a.log = log && std::all_of(values.begin(), values.end(), [](double v) { return !std::isfinite(v) || v > 0; });
        double lo = INFINITY, hi = -INFINITY;
        for (double v : values)
            if (std::isfinite(v))
                lo = std::min(lo, a.log ? std::log10(v) : v), hi = std::max(hi, a.log ? std::log10(v) : v);
        if (!std::isfinite(lo)) lo = 0, hi = 1;
        const double pad = hi > lo ? 0.08 * (hi - lo) : std::max(0.5, std::abs(lo) * 0.1);
        a.lo = lo - pad, a.hi = hi + pad;
        return a;
    }
    double at(double v, double length) const { return ((log ? std::log10(v) : v) - lo) / (hi - lo) * length; }
    std::vector<double> ticks() const {
        std::vector<double> out;
        if (log) {
            // 1, 2, 5 per decade; where the axis spans less than that gives three ticks, every digit.
            for (const std::vector<double>& mantissas :
                 {std::vector<double>{1, 2, 5}, std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
                out.clear();
                for (double e = std::floor(lo); e <= hi; e += 1)
                    for (double m : mantissas) {
                        const double t = std::log10(m) + e;
                        if (t >= lo && t <= hi) out.push_back(std::pow(10.0, t));
                    }
                if (out.size() >= 3) break;
            }
            return out;
        }
        const double raw = (hi - lo) / 5, step = std::pow(10.0, std::floor(std::log10(raw)));
        const double nice = raw / step < 2 ? step : raw / step < 5 ? 2 * step : 5 * step;
        for (double t = std::ceil(lo / nice) * nice; t <= hi; t += nice)
            out.push_back(std::abs(t) < nice * 1e-9 ? 0 : t);
        return out;
    }
};

// A rectangle of pixels [x0, x1) x [y0, y1): a label's or a point's, to keep labels apart.
struct Box {
    int x0, y0, x1, y1;
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Where a point's label goes: beside it (right or left, above or below) where it overlaps no
// label placed before and no point, else moved up or down a line at a time (a leader line
// then joins it to its point); inside the plot area `area`.
Box placeLabel(double x, double y, int width, const Box& area, const std::vector<Box>& taken) {
    const int h = Canvas::kTextHeight, px = static_cast<int>(x), py = static_cast<int>(y);
    auto inside = [&](Box b) {
        const int dx = std::max(0, area.x0 - b.x0) - std::max(0, b.x1 - area.x1);
        const int dy = std::max(0, area.y0 - b.y0) - std::max(0, b.y1 - area.y1);
        return Box{b.x0 + dx, b.y0 + dy, b.x1 + dx, b.y1 + dy};
    };
    auto free = [&](const Box& b) {
        return std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); });
    };
    std::vector<Box> candidates;
    for (int shift = 0; shift <= 8; ++shift)
        for (int side : {1, -1}) {  // the line above the point, then the one below, moving away
            const int top = side > 0 ? py - h - 2 - shift * (h + 2) : py + 2 + shift * (h + 2);
            candidates.push_back(inside({px + 8, top, px + 8 + width, top + h}));
            candidates.push_back(inside({px - 8 - width, top, px - 8, top + h}));
        }
    for (const Box& b : candidates)
        if (free(b)) return b;
    return candidates.front();  // crowded everywhere: beside the point, as before
}

void drawPanel(Canvas& canvas, int left, int top, const ChartPanel& p) {
    std::vector<double> xs, ys;
    for (const ChartSeries& s : p.series) {
        BTFLUT_CHECK(s.x.size() == s.y.size());
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) xs.push_back(s.x[i]), ys.push_back(s.y[i]);
    }
    const Axis ax = Axis::of(xs, p.logX), ay = Axis::of(ys, false);
    const int x0 = left + kLeft, y0 = top + kTop;
    auto px = [&](double x) { return x0 + ax.at(x, kPanelW); };
    auto py = [&](double y) { return y0 + kPanelH - ay.at(y, kPanelH); };
    const std::string title = Canvas::fitted(p.title, kPanelW + kLeft - 8);
    canvas.text(std::max(left + 4, x0 + (kPanelW - Canvas::textWidth(title)) / 2), top + 2, title, kInk);
    // Series with no point to draw (a mode eval did not time: --no-gl) are named, not dropped unseen.
    std::string missing;
    for (const ChartSeries& s : p.series) {
        bool any = false;
        for (std::size_t i = 0; i < s.x.size(); ++i) any = any || (std::isfinite(s.x[i]) && std::isfinite(s.y[i]));
        if (!any) missing += (missing.empty() ? "" : ", ") + s.label;
    }
    if (!missing.empty() && !xs.empty())
        canvas.text(x0 + 4, top + 4 + Canvas::kTextHeight, Canvas::fitted("no figure: " + missing, kPanelW - 8),
                    kAxisGrey);
    canvas.fill(x0, y0 + kPanelH, x0 + kPanelW, y0 + kPanelH + 1, kAxisGrey);
    canvas.fill(x0, y0, x0 + 1, y0 + kPanelH, kAxisGrey);
    if (xs.empty()) {
        canvas.text(x0 + 20, y0 + kPanelH / 2, "no figures", kAxisGrey);
        return;
    }
    int lastTickEnd = -1000;  // a tick's number is skipped where it would touch the previous one's
    const std::vector<double> xTicks = ax.ticks(), yTicks = ay.ticks();
    for (double t : xTicks) {
        const std::string text = tickText(t, spacingOf(xTicks, ax.log));
        const int x = static_cast<int>(px(t)), from = x - Canvas::textWidth(text) / 2;
        canvas.fill(x, y0 + kPanelH, x + 1, y0 + kPanelH + 6, kAxisGrey);
        if (from < lastTickEnd + 8) continue;
        canvas.text(from, y0 + kPanelH + 8, text, kInk);
        lastTickEnd = from + Canvas::textWidth(text);
    }
    for (double t : yTicks) {
        const std::string text = tickText(t, spacingOf(yTicks, false));
        const int y = static_cast<int>(py(t));
        canvas.fill(x0 - 6, y, x0, y + 1, kAxisGrey);
        canvas.text(x0 - 10 - Canvas::textWidth(text), y - Canvas::kTextHeight / 2, text, kInk);
    }
    canvas.text(x0 + (kPanelW - Canvas::textWidth(p.xLabel)) / 2, y0 + kPanelH + 30, p.xLabel, kAxisGrey);
    canvas.text(x0 + 6, top + 20, p.yLabel, kAxisGrey);  // above the plot, clear of the y ticks' numbers
    if (p.pareto != Better::None && !p.lines) {          // the front first, under the points
        std::vector<double> cost, value;
        for (const ChartSeries& s : p.series)
            for (std::size_t i = 0; i < s.x.size(); ++i) cost.push_back(s.x[i]), value.push_back(s.y[i]);
        const std::vector<std::size_t> front = paretoFront(cost, value, p.pareto);
        for (std::size_t k = 1; k < front.size(); ++k) {  // a staircase: each point is best up to the next's cost
            const double xa = px(cost[front[k - 1]]), ya = py(value[front[k - 1]]), xb = px(cost[front[k]]),
                         yb = py(value[front[k]]);
            canvas.line(xa, ya, xb, ya, {0.8f, 0.8f, 0.8f}, 3);
            canvas.line(xb, ya, xb, yb, {0.8f, 0.8f, 0.8f}, 3);
        }
        for (std::size_t k : front) canvas.dot(px(cost[k]), py(value[k]), 13, {0.85f, 0.85f, 0.85f});
    }
    // Every point's box first, so that no label covers a point drawn after it.
    std::vector<Box> taken;
    for (const ChartSeries& series : p.series)
        for (std::size_t i = 0; i < series.x.size(); ++i)
            if (!p.lines && std::isfinite(series.x[i]) && std::isfinite(series.y[i]))
                taken.push_back({static_cast<int>(px(series.x[i])) - 4, static_cast<int>(py(series.y[i])) - 4,
                                 static_cast<int>(px(series.x[i])) + 5, static_cast<int>(py(series.y[i])) + 5});
    const Box area{x0 + 2, y0, x0 + kPanelW, y0 + kPanelH - 2};
    int legendY = y0 + 4;
    for (std::size_t s = 0; s < p.series.size(); ++s) {
        const ChartSeries& series = p.series[s];
        const Rgb colour = paletteColour(s);
        double lastX = NAN, lastY = NAN;
        for (std::size_t i = 0; i < series.x.size(); ++i) {
            if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
            const double x = px(series.x[i]), y = py(series.y[i]);
            if (p.lines && std::isfinite(lastX)) canvas.line(lastX, lastY, x, y, colour, 2);
            canvas.dot(x, y, p.lines ? 5 : 7, colour);
            if (!p.lines) {  // the label beside the point, clear of the others, inside the panel
                const std::string label = Canvas::fitted(series.label, 160);
                const Box at = placeLabel(x, y, Canvas::textWidth(label), area, taken);
                taken.push_back(at);
                // Moved off its point: a leader from the point to the label's nearest edge.
                const double lx = std::clamp(x, at.x0 - 2.0, at.x1 + 2.0), ly = std::clamp(y, at.y0 - 1.0, at.y1 + 1.0);
                if (ly != y && std::hypot(lx - x, ly - y) > 6) canvas.line(x, y, lx, ly, colour, 1);
                canvas.text(at.x0, at.y0, label, colour);
            }
            lastX = x, lastY = y;
        }
        if (p.lines) {  // the legend, right of the plot
            const std::string label = Canvas::fitted(series.label, kLegendW - 30);
            const int tx = x0 + kPanelW + kRight + 22;
            canvas.fill(tx - 22, legendY + 5, tx - 6, legendY + 8, colour);
            canvas.text(tx, legendY, label, colour);
            legendY += Canvas::kTextHeight + 4;
        }
    }
}

}  // namespace

std::vector<std::string> axisTickLabels(const std::vector<double>& values, bool log) {
    const Axis axis = Axis::of(values, log);
    const std::vector<double> ticks = axis.ticks();
    std::vector<std::string> out;
    for (double t : ticks) out.push_back(tickText(t, spacingOf(ticks, axis.log)));
    return out;
}

std::vector<std::size_t> paretoFront(const std::vector<double>& cost, const std::vector<double>& value, Better better) {
    BTFLUT_CHECK(cost.size() == value.size() && better != Better::None);
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < cost.size(); ++i)
        if (std::isfinite(cost[i]) && std::isfinite(value[i])) order.push_back(i);
    const double sign = better == Better::Higher ? 1 : -1;  // larger `sign * value` is better
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return cost[a] != cost[b] ? cost[a] < cost[b] : sign * value[a] > sign * value[b];
    });
    std::vector<std::size_t> front;
    for (std::size_t i : order)
        if (front.empty() || sign * value[i] > sign * value[front.back()]) front.push_back(i);
    return front;
}

Image drawCharts(const std::vector<ChartPanel>& panels, int columns) {
    BTFLUT_CHECK(!panels.empty() && columns > 0);
    const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
    const int across = std::min(columns, static_cast<int>(panels.size()));
    const bool legends = std::any_of(panels.begin(), panels.end(), [](const ChartPanel& p) { return p.lines; });
    const int cellW = kCellW + (legends ? kLegendW : 0);
    Canvas canvas(across * cellW, rows * kCellH);
    for (std::size_t i = 0; i < panels.size(); ++i)
        drawPanel(canvas, static_cast<int>(i) % columns * cellW, static_cast<int>(i) / columns * kCellH, panels[i]);
    return canvas.take();
}

}  // namespace btflut
