#include "core/inverse/classify.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace btflut {

namespace {

double mean(const std::vector<double>& histogram) {
    double sum = 0, mass = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        sum += histogram[b] * (static_cast<double>(b) + 0.5) / static_cast<double>(histogram.size());
        mass += histogram[b];
    }
    return mass > 0 ? sum / mass : 0;
}

}  // namespace

MaterialMatch matchMaterial(const std::vector<double>& histogram, const MaterialHistograms& material, Direction view,
                            Metric metric) {
    const int bins = static_cast<int>(histogram.size());
    const double target = mean(histogram);
    auto score = [&](DiskPoint p, int nodes) {
        const std::vector<double> predicted = material.at(fromDisk(p), view, bins, nodes);
        return metric == Metric::Histogram ? earthMoversDistance(histogram, predicted)
                                           : std::abs(mean(predicted) - target);
    };
    // A grid over the disk (lights up to the horizon), then a pattern search from the best.
    constexpr int kGrid = 21;
    std::vector<DiskPoint> points;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const DiskPoint p{-1 + 2.0 * i / (kGrid - 1), -1 + 2.0 * j / (kGrid - 1)};
            if (p.x * p.x + p.y * p.y <= 1) points.push_back(p);
        }
    DiskPoint best = points.front();
    double bestScore = score(best, 16);
    for (const DiskPoint& p : points)
        if (const double s = score(p, 16); s < bestScore) {
            bestScore = s;
            best = p;
        }
    bestScore = score(best, 32);
    for (double step = 1.0 / (kGrid - 1); step > 1e-3; step /= 2) {
        bool moved = true;
        while (moved) {
            moved = false;
            for (auto [dx, dy] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}}) {
                const DiskPoint p{best.x + dx, best.y + dy};
                if (p.x * p.x + p.y * p.y > 1) continue;
                if (const double s = score(p, 32); s < bestScore) {
                    bestScore = s;
                    best = p;
                    moved = true;
                }
            }
        }
    }
    return {0, bestScore, fromDisk(best)};
}

std::vector<MaterialMatch> classify(const std::vector<double>& histogram,
                                    const std::vector<MaterialHistograms>& library, Direction view, Metric metric) {
    std::vector<MaterialMatch> matches(library.size());
    parallelFor(library.size(), 0, [&](std::size_t m) {
        matches[m] = matchMaterial(histogram, library[m], view, metric);
        matches[m].material = m;
    });
    std::stable_sort(matches.begin(), matches.end(), [](const auto& a, const auto& b) { return a.score < b.score; });
    return matches;
}

}  // namespace btflut
