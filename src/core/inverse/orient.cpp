#include "core/inverse/orient.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace btflut {

namespace {

constexpr double kInfinite = std::numeric_limits<double>::infinity();

Vec3 rotate(Vec3 v, Vec3 axis, double angle) {  // Rodrigues, axis of unit length
    const double c = std::cos(angle), s = std::sin(angle);
    const double dot = axis.x * v.x + axis.y * v.y + axis.z * v.z;
    const Vec3 cross{axis.y * v.z - axis.z * v.y, axis.z * v.x - axis.x * v.z, axis.x * v.y - axis.y * v.x};
    return {v.x * c + cross.x * s + axis.x * dot * (1 - c), v.y * c + cross.y * s + axis.y * dot * (1 - c),
            v.z * c + cross.z * s + axis.z * dot * (1 - c)};
}

// A frame vector in the sample frame of normal (tilt, azimuth): turned back by the tilt.
Vec3 inSampleFrame(Vec3 v, double tilt, double azimuth) {
    const Vec3 axis{-std::sin(azimuth), std::cos(azimuth), 0};  // z x n, normalised
    return rotate(v, axis, -tilt);
}

struct Evaluation {
    double distance = kInfinite;
    Direction light, view;
};

class Search {
public:
    Search(const std::vector<double>& histogram, const MaterialHistograms& material, Direction known, Known which,
           int bins)
        : m_histogram(histogram), m_material(material), m_known(toVector(known)), m_which(which), m_bins(bins) {}

    Evaluation at(double tilt, double azimuth, int nodes) const {
        const Vec3 axis = inSampleFrame({0, 0, 1}, tilt, azimuth), other = inSampleFrame(m_known, tilt, azimuth);
        constexpr double kHorizon = 0.0175;  // cos(89 degrees): the sample must face light and camera
        if (axis.z < kHorizon || other.z < kHorizon) return {};
        Evaluation e;
        e.light = fromVector(m_which == Known::Light ? other : axis);
        e.view = fromVector(m_which == Known::Light ? axis : other);
        e.distance = earthMoversDistance(m_histogram, m_material.at(e.light, e.view, m_bins, nodes));
        return e;
    }

private:
    const std::vector<double>& m_histogram;
    const MaterialHistograms& m_material;
    Vec3 m_known;
    Known m_which;
    int m_bins;
};

// The connected regions of a rows x columns grid of costs (row 0 the pole, one cell;
// azimuth wraps) whose cost is within `within`, each a list of cells.
std::vector<std::vector<std::size_t>> regionsWithin(const std::vector<double>& cost, int rows, int columns,
                                                    double within) {
    std::vector<int> region(cost.size(), -1);
    std::vector<std::vector<std::size_t>> regions;
    for (std::size_t seed = 0; seed < cost.size(); ++seed) {
        if (region[seed] >= 0 || cost[seed] > within) continue;
        regions.emplace_back();
        std::vector<std::size_t> stack{seed};
        region[seed] = static_cast<int>(regions.size() - 1);
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            regions.back().push_back(i);
            const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
            for (int dr = -1; dr <= 1; ++dr)
                for (int dc = -1; dc <= 1; ++dc) {
                    const int nr = r + dr;
                    if (nr < 0 || nr >= rows) continue;
                    std::vector<int> ncs{(c + dc + columns) % columns};
                    if (r == 0 || nr == 0) {  // the pole touches every column of the first ring
                        ncs.clear();
                        for (int k = 0; k < columns; ++k) ncs.push_back(k);
                    }
                    for (int nc : ncs) {
                        const std::size_t n = static_cast<std::size_t>(nr) * columns + nc;
                        if (region[n] < 0 && cost[n] <= within) {
                            region[n] = region[seed];
                            stack.push_back(n);
                        }
                    }
                }
        }
    }
    return regions;
}

}  // namespace

Result<Orientation> estimateOrientation(const std::vector<double>& histogram, const MaterialHistograms& material,
                                        Direction known, Known which, double tolerance, const OrientOptions& options) {
    if (histogram.size() != static_cast<std::size_t>(options.bins))
        return Error{"the histogram has the wrong number of bins"};
    double mass = 0;
    for (double v : histogram) mass += v;
    if (!(mass > 0)) return Error{"the histogram is empty (no sample pixels)"};
    if (!(known.theta >= 0 && known.theta < 90 * kDegree))
        return Error{std::string("the known ") + (which == Known::Light ? "light" : "view") +
                     " must be above the horizon"};
    const Search search(histogram, material, known, which, options.bins);

    // The grid: tilt rows (row 0 is the pole, one normal) by azimuth columns.
    const int rows = static_cast<int>(std::floor(options.maxTilt / options.tiltStep + 1e-9)) + 1;
    const int columns = static_cast<int>(std::lround(2 * std::numbers::pi / options.azimuthStep));
    auto tiltOf = [&](int r) { return r * options.tiltStep; };
    auto azimuthOf = [&](int c) { return c * 2 * std::numbers::pi / columns; };
    std::vector<double> cost(static_cast<std::size_t>(rows) * columns, kInfinite);
    parallelFor(cost.size(), 0, [&](std::size_t i) {
        const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
        if (r == 0 && c > 0) return;  // the pole, once
        cost[i] = search.at(tiltOf(r), azimuthOf(c), 24).distance;
    });
    std::fill(cost.begin() + 1, cost.begin() + columns, cost[0]);
    const double best = *std::min_element(cost.begin(), cost.end());
    if (!std::isfinite(best)) return Error{"no orientation faces both the light and the camera"};

    // Regions within the tolerance of the best, connected over the grid (azimuth wraps).
    const std::vector<std::vector<std::size_t>> regions = regionsWithin(cost, rows, columns, best + tolerance);

    // Each region's best normal, refined by a pattern search at the finer quadrature.
    Orientation out;
    out.tolerance = tolerance;
    for (const std::vector<std::size_t>& cells : regions) {
        const std::size_t start =
            *std::min_element(cells.begin(), cells.end(), [&](auto a, auto b) { return cost[a] < cost[b]; });
        double tilt = tiltOf(static_cast<int>(start) / columns), azimuth = azimuthOf(static_cast<int>(start) % columns);
        Evaluation e = search.at(tilt, azimuth, 32);
        for (double step = options.tiltStep / 2; step > 0.02 * kDegree; step /= 2) {
            bool moved = true;
            while (moved) {
                moved = false;
                const double azimuthStep = step / std::max(std::sin(tilt), 0.05);
                for (auto [dt, da] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, azimuthStep}, {0.0, -azimuthStep}}) {
                    double t = tilt + dt, a = azimuth + da;
                    if (t < 0) {  // through the pole
                        t = -t;
                        a += std::numbers::pi;
                    }
                    if (t > options.maxTilt) continue;
                    const Evaluation trial = search.at(t, a, 32);
                    if (trial.distance < e.distance) {
                        e = trial;
                        tilt = t;
                        azimuth = std::fmod(a + 4 * std::numbers::pi, 2 * std::numbers::pi);
                        moved = true;
                    }
                }
            }
        }
        OrientationCandidate candidate{Direction{tilt, azimuth}, e.light, e.view, e.distance};
        candidate.cells = cells;
        out.candidates.push_back(candidate);
    }
    std::sort(out.candidates.begin(), out.candidates.end(),
              [](const auto& a, const auto& b) { return a.distance < b.distance; });

    // Spreads over each candidate's region; a region within another's spread is one answer
    // with it (the costs' noise splits regions the histogram cannot tell apart either).
    auto spread = [&](OrientationCandidate& c) {
        c.uncertainty = c.tiltUncertainty = options.tiltStep / 2;  // the grid's own resolution
        std::vector<bool> columnSeen(static_cast<std::size_t>(columns), false);
        for (std::size_t i : c.cells) {
            const int r = static_cast<int>(i) / columns;
            const Direction n{tiltOf(r), azimuthOf(static_cast<int>(i) % columns)};
            c.uncertainty = std::max(c.uncertainty, angleBetween(n, c.normal));
            c.tiltUncertainty = std::max(c.tiltUncertainty, std::abs(n.theta - c.normal.theta));
            if (r > 0) columnSeen[i % static_cast<std::size_t>(columns)] = true;
        }
        c.azimuthDetermined = std::count(columnSeen.begin(), columnSeen.end(), true) < columns * 9 / 10;
    };
    for (OrientationCandidate& c : out.candidates) spread(c);
    for (std::size_t a = 0; a < out.candidates.size(); ++a)
        for (std::size_t b = a + 1; b < out.candidates.size();) {
            OrientationCandidate &keep = out.candidates[a], &other = out.candidates[b];
            if (angleBetween(keep.normal, other.normal) > keep.uncertainty + other.uncertainty) {
                ++b;
                continue;
            }
            keep.cells.insert(keep.cells.end(), other.cells.begin(), other.cells.end());
            out.candidates.erase(out.candidates.begin() + static_cast<std::ptrdiff_t>(b));
            spread(keep);
            b = a + 1;
        }
    for (OrientationCandidate& c : out.candidates) c.cells.clear();
    return out;
}

double histogramTolerance(const Image& image, const Mask& mask, int bins) {
    auto half = [&](bool vertical, bool first) {
        Mask part = mask;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const bool inFirst = vertical ? x < image.width / 2 : y < image.height / 2;
                if (inFirst != first) part.inside[static_cast<std::size_t>(y) * image.width + x] = 0;
            }
        return part.count() ? binHistogram(countGreyLevels(image, part), bins) : std::vector<double>();
    };
    double sum = 0;
    int pairs = 0;
    for (bool vertical : {true, false}) {
        const std::vector<double> a = half(vertical, true), b = half(vertical, false);
        if (a.empty() || b.empty()) continue;
        sum += earthMoversDistance(a, b);
        ++pairs;
    }
    // Two halves differ by about twice what the whole image differs from its expectation.
    return std::max(pairs ? sum / pairs / 2 : 0.0, 0.25 / bins);
}

}  // namespace btflut
