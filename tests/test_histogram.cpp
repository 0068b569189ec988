#include <doctest/doctest.h>

#include "core/histogram/histogram.h"
#include "core/histogram/plot.h"
#include "core/image/canvas.h"

using namespace btflut;

TEST_CASE("grey levels are exact codes of the mean of R, G, B within the mask") {
    Image im(2, 2, 3);
    const float px[4][3] = {{0, 0, 0}, {1, 1, 1}, {10 / 255.f, 20 / 255.f, 30 / 255.f}, {1, 0, 0}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) im.samples[i * 3 + c] = px[i][c];
    Mask mask{2, 2, {1, 1, 1, 0}};
    LevelCounts grey = countGreyLevels(im, mask);
    CHECK(grey.counts.size() == 766);
    CHECK(grey.total() == 3);
    CHECK(grey.counts[0] == 1);
    CHECK(grey.counts[765] == 1);
    CHECK(grey.counts[60] == 1);
    CHECK(grey.counts[255] == 0);  // masked out
    LevelCounts red = countChannelLevels(im, fullMask(2, 2), 0);
    CHECK(red.counts.size() == 256);
    CHECK(red.counts[255] == 2);
}

TEST_CASE("binned histograms are normalised and put 1.0 in the last bin") {
    LevelCounts l{{1, 0, 0, 1}};  // values 0 and 1
    auto h = binHistogram(l, 4);
    CHECK(h[0] == 0.5);
    CHECK(h[3] == 0.5);
    LevelCounts many;
    many.counts.assign(766, 3);
    auto h64 = binHistogram(many, 64);
    double sum = 0;
    for (double v : h64) sum += v;
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-15));
}

TEST_CASE("histogram CSV round-trips and refuses malformed rows") {
    std::vector<HistogramRow> rows{{"a", Direction::fromDegrees(30, 45), Direction::fromDegrees(0, 0), {0.25, 0.75}},
                                   {"b", Direction::fromDegrees(10, 0), Direction::fromDegrees(20, 90), {1, 0}}};
    std::string csv = histogramsToCsv(rows);
    CHECK(csv.rfind("name,theta_i,phi_i,theta_r,phi_r,b0,b1\n", 0) == 0);
    auto back = parseHistogramCsv(csv, "h.csv");
    REQUIRE(back.ok());
    REQUIRE(back->size() == 2);
    CHECK((*back)[1].bins == rows[1].bins);
    CHECK((*back)[0].light.thetaDegrees() == doctest::Approx(30));
    CHECK((*back)[1].view.phiDegrees() == doctest::Approx(90));
    CHECK(histogramsToCsv(*back) == csv);

    for (const char* bad : {"", "name,theta_i\n", "name,theta_i,phi_i,theta_r,phi_r,b0,b2\n",
                            "name,theta_i,phi_i,theta_r,phi_r,b0,b1\na,1,2,3,4,0.5\n",
                            "name,theta_i,phi_i,theta_r,phi_r,b0,b1\na,1,2,3,4,0.5,x\n",
                            "name,theta_i,phi_i,theta_r,phi_r,b0,b1\na,nan,2,3,4,0.5,0.5\n",
                            "name,theta_i,phi_i,theta_r,phi_r,b0,b1\na,1,2,3,4,-0.5,1.5\n"}) {
        INFO(bad);
        auto r = parseHistogramCsv(bad, "h.csv");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("h.csv") == 0);
    }
}

TEST_CASE("earth mover's distance of shifted spikes is the shift") {
    std::vector<double> a(10, 0), b(10, 0);
    a[2] = 1;
    b[5] = 1;
    CHECK(earthMoversDistance(a, b) == doctest::Approx(0.3));
    CHECK(earthMoversDistance(a, a) == 0.0);
}

TEST_CASE("contact sheet: a label's lines ('\\n' between them) are drawn one under the other") {
    Image cell(16, 16, 3);
    std::fill(cell.samples.begin(), cell.samples.end(), 0.5f);
    const Image one = contactSheet({{{"photo", cell}}}, 64), two = contactSheet({{{"photo\n12.3 dB", cell}}}, 64);
    CHECK(two.height == one.height + Canvas::kTextHeight + 5);  // a line more for every cell
    // The second line's rows have ink, and none with a blank second line.
    const int from = 8 + 2 + Canvas::kTextHeight + 5, to = from + Canvas::kTextHeight;
    auto inked = [&](const Image& image) {
        for (int y = from; y < to; ++y)
            for (int x = 0; x < image.width; ++x)
                if (image.samples[(static_cast<std::size_t>(y) * image.width + x) * 3] != image.samples[0]) return true;
        return false;
    };
    CHECK(inked(two));
    CHECK_FALSE(inked(contactSheet({{{"photo\n ", cell}}}, 64)));
}

TEST_CASE("histogram figure against the first column: its bars under every panel, each column's outline in its own") {
    auto row = [](int peak) {
        HistogramRow r;
        r.name = "light";
        r.bins.assign(8, 0.0);
        r.bins[static_cast<std::size_t>(peak)] = 1;
        return r;
    };
    const std::vector<PlotColumn> columns{{"measured", {row(2)}}, {"a", {row(2)}}, {"b", {row(6)}}};
    const PlotStyle style{.layout = PlotStyle::Layout::AgainstFirst, .panelWidth = 160, .panelHeight = 80};
    const Image figure = plotHistograms(columns, style);
    const Image paper = plotHistograms(columns, {.panelWidth = 160, .panelHeight = 80});
    CHECK(figure.width < paper.width);  // two panels, not three: the first column is in both
    // Count the bars' colour in each panel's x range: the measured peak (bin 2 of 8) in both.
    const Rgb bar = paletteColour(0), outline = paletteColour(2);
    auto count = [&](Rgb c, int x0, int x1) {
        int n = 0;
        for (int y = 0; y < figure.height; ++y)
            for (int x = x0; x < x1; ++x)
                if (std::abs(figure.at(x, y, 0) - c.r) < 1e-3f && std::abs(figure.at(x, y, 1) - c.g) < 1e-3f &&
                    std::abs(figure.at(x, y, 2) - c.b) < 1e-3f)
                    ++n;
        return n;
    };
    const int right = figure.width - 160 - 36;             // the second panel's left edge
    CHECK(count(bar, right - 196, right - 36) > 20 * 60);  // a bar of a fifth of the panel, nearly full height
    CHECK(count(bar, right, right + 160) > 20 * 60);
    // b's outline (its peak at bin 6) only in the second panel, near its right.
    CHECK(count(outline, right, right + 160) > 20);
    CHECK(count(outline, right + 110, right + 140) > 20);
    CHECK(count(outline, right - 196, right - 36) < 10);  // its title's colour is above the panels, not in them
}
