#include "core/histogram/plot.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/image/canvas.h"

namespace btflut {

namespace {

constexpr int kGapX = 36, kGapY = 10;
constexpr int kLeft = 96, kTop = 44, kBottom = 44;

const Rgb kBar = paletteColour(0), kAxis = kAxisGrey, kMark{0.75f, 0.15f, 0.1f};

std::string positionLabel(const std::string& name) {
    if (name == "c2-4") return name + " L";
    if (name == "c2-6") return name + " S";
    if (name == "c2-8") return name + " C";
    return name;
}

std::string format(const char* pattern, double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, pattern, v);
    return buf;
}

// A histogram in the panel at (x0, y0), its bins scaled so that `rowMax` fills the panel: bars,
// or a step outline (each bin's top, and the rise from the previous one).
void drawBins(Canvas& canvas, const std::vector<double>& bins, int x0, int y0, int panelW, int panelH, double rowMax,
              Rgb colour, bool bars) {
    const auto n = static_cast<int>(bins.size());
    int previous = -1;
    for (int b = 0; b < n; ++b) {
        const int bx0 = x0 + 1 + b * (panelW - 1) / n, bx1 = std::max(x0 + 1 + (b + 1) * (panelW - 1) / n, bx0 + 1);
        const int barHeight = static_cast<int>(bins[static_cast<std::size_t>(b)] / rowMax * (panelH - 4) + 0.5);
        const int y = y0 + panelH - barHeight;
        if (bars) {
            canvas.fill(bx0, y, bx1, y0 + panelH, colour);
        } else {
            canvas.fill(bx0, y - 1, bx1, y + 1, colour);
            if (previous >= 0) canvas.fill(bx0, std::min(previous, y) - 1, bx0 + 2, std::max(previous, y) + 1, colour);
        }
        previous = y;
    }
}

}  // namespace

Image plotHistograms(const std::vector<PlotColumn>& columns, const PlotStyle& style) {
    using Layout = PlotStyle::Layout;
    BTFLUT_CHECK(!columns.empty() && style.panelWidth > 16 && style.panelHeight > 16);
    const int panelW = style.panelWidth, panelH = style.panelHeight;
    const bool paper = style.layout == Layout::Columns, against = style.layout == Layout::AgainstFirst;
    BTFLUT_CHECK(!against || columns.size() > 1);
    std::size_t rows = 0;
    for (const PlotColumn& c : columns) rows = std::max(rows, c.rows.size());
    BTFLUT_CHECK(rows > 0);
    auto labelOf = [&](std::size_t r) {
        for (const PlotColumn& c : columns)
            if (r < c.rows.size()) return positionLabel(c.rows[r].name);
        return std::string();
    };
    auto peakOf = [](const HistogramRow& row) { return *std::max_element(row.bins.begin(), row.bins.end()); };
    // A common y axis: a position's largest bin over every column, its ticks left of the panels.
    std::vector<double> common(rows, 0);
    for (std::size_t r = 0; r < rows; ++r)
        for (const PlotColumn& c : columns)
            if (r < c.rows.size()) common[r] = std::max(common[r], peakOf(c.rows[r]));
    int ticksW = 0;
    if (!paper)
        for (double top : common) ticksW = std::max(ticksW, Canvas::textWidth(format("%.3f", top)) + 8);
    int left = kLeft;  // fits the longest row label
    for (std::size_t r = 0; r < rows; ++r) left = std::max(left, Canvas::textWidth(labelOf(r)) + 16);
    left += ticksW;
    const int panels = style.layout == Layout::Overlay ? 1 : static_cast<int>(columns.size()) - (against ? 1 : 0);
    const int legendLines = style.layout == Layout::Overlay ? static_cast<int>(columns.size()) : against ? 2 : 0;
    const int top = kTop + 18 * legendLines + (paper ? 0 : 18);  // legend, the y axis's name
    const int width = left + panels * (panelW + kGapX);
    const int height = top + static_cast<int>(rows) * (panelH + kGapY) + kBottom;
    Canvas canvas(width, height);
    auto colourOf = [](std::size_t c) { return paletteColour(c); };  // the first: the bars
    auto fitted = [&](const std::string& title) { return Canvas::fitted(title, panelW); };
    // Which columns a panel draws, and where: the paper's one each, Overlay all in one, AgainstFirst the first and one.
    auto panelOf = [&](std::size_t c) { return paper ? static_cast<int>(c) : against ? static_cast<int>(c) - 1 : 0; };
    auto panelX = [&](int panel) { return left + panel * (panelW + kGapX); };
    if (style.layout == Layout::Overlay) {  // the legend
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const int y = 8 + 18 * static_cast<int>(c);
            canvas.fill(left, y + 3, left + 24, y + 11, colourOf(c));
            canvas.text(left + 32, y, fitted(columns[c].title), kInk);
        }
    } else {
        if (against) {  // the legend: bars the first column, the outline the panel's
            canvas.fill(left, 11, left + 24, 19, colourOf(0));
            canvas.text(left + 32, 8, "bars: " + columns.front().title, kInk);
            canvas.fill(left, 32, left + 24, 34, colourOf(1));
            canvas.text(left + 32, 26, "lines: each panel's, in its title's colour", kInk);
        }
        for (std::size_t c = against ? 1 : 0; c < columns.size(); ++c) {
            const int x0 = panelX(panelOf(c));
            const std::string title = fitted(columns[c].title);
            canvas.text(x0 + (panelW - Canvas::textWidth(title)) / 2, top - 24 - (paper ? 0 : 18), title,
                        against ? colourOf(c) : kInk);
        }
    }
    if (!paper) canvas.text(left - ticksW, top - 20, "fraction of texels", kAxis);  // the common y axis's name
    for (std::size_t r = 0; r < rows; ++r) {
        const int y0 = top + static_cast<int>(r) * (panelH + kGapY);
        const std::string label = labelOf(r);
        const bool marked = label.size() > 2 && label[label.size() - 2] == ' ';
        canvas.text(8, y0 + 20, label, marked ? kMark : kInk);
        if (!paper && common[r] > 0)  // the common scale's ticks: 0, half, the top
            for (double t : {0.0, 0.5, 1.0}) {
                const int y = y0 + panelH - static_cast<int>(t * (panelH - 4) + 0.5);
                const std::string tick = t == 0 ? "0" : format("%.3f", t * common[r]);
                canvas.text(left - 6 - Canvas::textWidth(tick),
                            std::clamp(y - Canvas::kTextHeight / 2, y0, y0 + panelH), tick, kAxis);
                canvas.fill(left - 4, y, left, y + 1, kAxis);
            }
        for (int p = 0; p < panels; ++p) {
            const int x0 = panelX(p);
            canvas.fill(x0, y0 + panelH, x0 + panelW, y0 + panelH + 1, kAxis);  // baseline
            canvas.fill(x0, y0, x0 + 1, y0 + panelH, kAxis);                    // y axis
        }
        for (std::size_t c = 0; c < columns.size(); ++c) {
            if (r >= columns[c].rows.size()) continue;
            const std::vector<double>& bins = columns[c].rows[r].bins;
            const double rowMax = paper ? peakOf(columns[c].rows[r]) : common[r];
            if (rowMax <= 0) continue;
            // AgainstFirst: the first column's bars under every panel, each later column's outline in its own.
            std::vector<int> targets;
            if (against && c == 0)
                for (int p = 0; p < panels; ++p) targets.push_back(p);
            else
                targets.push_back(panelOf(c));
            for (int panel : targets)
                drawBins(canvas, bins, panelX(panel), y0, panelW, panelH, rowMax, c == 0 ? kBar : colourOf(c), c == 0);
            if (!paper) continue;
            // The panel's own scale, over the bars on a white backing.
            const int x0 = panelX(panelOf(c));
            const std::string scale = format("%.3f", rowMax);
            const int tx = x0 + panelW - Canvas::textWidth(scale) - 2;
            canvas.fill(tx - 2, y0, x0 + panelW, y0 + 16, {1, 1, 1});
            canvas.text(tx, y0 + 2, scale, kAxis);
        }
    }
    // Grey-value axis under the last row of each panel.
    const int axisY = top + static_cast<int>(rows) * (panelH + kGapY) + 2;
    for (int p = 0; p < panels; ++p) {
        const int x0 = panelX(p);
        for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const int x = x0 + static_cast<int>(t * (panelW - 1));
            canvas.fill(x, axisY - 6, x + 1, axisY, kAxis);
            const std::string tick = t == 0 ? "0" : t == 1 ? "1" : format("%.2g", t);
            canvas.text(std::clamp(x - Canvas::textWidth(tick) / 2, 0, width - Canvas::textWidth(tick)), axisY + 2,
                        tick, kInk);
        }
        canvas.text(x0 + (panelW - Canvas::textWidth("grey value")) / 2, axisY + 22, "grey value", kAxis);
    }
    return canvas.take();
}

namespace {

// The image scaled to `width` pixels wide (box filter over the source pixels each output pixel covers), RGB.
Image scaledTo(const Image& image, int width) {
    const double step = static_cast<double>(image.width) / width;
    const int height = std::max(1, static_cast<int>(image.height / step));
    Image out(width, height, 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int x0 = static_cast<int>(x * step), x1 = std::max(x0 + 1, static_cast<int>((x + 1) * step));
            const int y0 = static_cast<int>(y * step), y1 = std::max(y0 + 1, static_cast<int>((y + 1) * step));
            float sum[3] = {0, 0, 0};
            int count = 0;
            for (int v = y0; v < std::min(y1, image.height); ++v)
                for (int u = x0; u < std::min(x1, image.width); ++u, ++count)
                    for (int c = 0; c < 3; ++c) sum[c] += image.at(u, v, image.channels == 1 ? 0 : c);
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = count ? sum[c] / static_cast<float>(count) : 0.f;
        }
    return out;
}

}  // namespace

Image contactSheet(const std::vector<std::vector<SheetCell>>& rows, int cellWidth) {
    BTFLUT_CHECK(!rows.empty() && !rows.front().empty() && cellWidth > 0);
    constexpr int kGap = 8, kLine = Canvas::kTextHeight + 5;
    std::size_t lines = 1;  // a label's lines ('\n' between them)
    for (const auto& row : rows)
        for (const SheetCell& cell : row)
            lines = std::max<std::size_t>(
                lines, 1 + static_cast<std::size_t>(std::count(cell.label.begin(), cell.label.end(), '\n')));
    const int kLabel = static_cast<int>(lines) * kLine + 4;
    std::size_t columns = 0;
    int cellHeight = 0;
    std::vector<std::vector<Image>> scaled;
    for (const auto& row : rows) {
        columns = std::max(columns, row.size());
        scaled.emplace_back();
        for (const SheetCell& cell : row) {
            scaled.back().push_back(scaledTo(cell.image, cellWidth));
            cellHeight = std::max(cellHeight, scaled.back().back().height);
        }
    }
    const int width = static_cast<int>(columns) * (cellWidth + kGap) + kGap;
    const int height = static_cast<int>(rows.size()) * (cellHeight + kLabel + kGap) + kGap;
    Canvas canvas(width, height);
    for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t c = 0; c < rows[r].size(); ++c) {
            const int x = kGap + static_cast<int>(c) * (cellWidth + kGap);
            const int y = kGap + static_cast<int>(r) * (cellHeight + kLabel + kGap);
            std::istringstream label(rows[r][c].label);
            int line = 0;
            for (std::string text; std::getline(label, text); ++line)  // each line clipped to its cell
                canvas.text(x, y + 2 + line * kLine, Canvas::fitted(text, cellWidth), line == 0 ? kInk : kAxisGrey);
            canvas.blit(x, y + kLabel, scaled[r][c]);
        }
    return canvas.take();
}

}  // namespace btflut
