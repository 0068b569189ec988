#include "core/triangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/check.h"

namespace btflut {

namespace {

double cross(DiskPoint o, DiskPoint a, DiskPoint b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// True when p lies strictly inside the circumcircle of the counter-clockwise triangle abc.
bool inCircumcircle(DiskPoint a, DiskPoint b, DiskPoint c, DiskPoint p) {
    double ax = a.x - p.x, ay = a.y - p.y, bx = b.x - p.x, by = b.y - p.y, cx = c.x - p.x,
           cy = c.y - p.y;
    double det = (ax * ax + ay * ay) * (bx * cy - cx * by) -
                 (bx * bx + by * by) * (ax * cy - cx * ay) +
                 (cx * cx + cy * cy) * (ax * by - bx * ay);
    return det > 1e-14;
}

// Closest point to p on segment ab, as the parameter t in [0, 1] and the squared distance.
std::pair<double, double> closestOnSegment(DiskPoint a, DiskPoint b, DiskPoint p) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0;
    double qx = a.x + t * dx - p.x, qy = a.y + t * dy - p.y;
    return {t, qx * qx + qy * qy};
}

constexpr double kAreaEpsilon = 1e-12;

}  // namespace

Triangulation::Triangulation(std::vector<DiskPoint> points) : m_points(std::move(points)) {
    BTFLUT_CHECK(!m_points.empty());
    const int n = static_cast<int>(m_points.size());
    bool collinear = true;
    for (int i = 2; i < n && collinear; ++i)
        collinear = std::abs(cross(m_points[0], m_points[1], m_points[i])) < kAreaEpsilon;

    if (n < 3 || collinear) {
        // A polyline: order the points along their common line.
        std::vector<int> order(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
        if (n >= 2) {
            DiskPoint a = m_points[0], b = m_points[1];
            auto along = [&](int i) {
                return (m_points[i].x - a.x) * (b.x - a.x) + (m_points[i].y - a.y) * (b.y - a.y);
            };
            std::sort(order.begin(), order.end(), [&](int i, int j) { return along(i) < along(j); });
        }
        for (std::size_t i = 1; i < order.size(); ++i) m_boundary.push_back({order[i - 1], order[i]});
        return;
    }

    // Bowyer-Watson with a super-triangle far outside the unit disk; its vertices are
    // n, n+1, n+2 in the working list.
    std::vector<DiskPoint> pts = m_points;
    pts.push_back({-1e4, -1e4});
    pts.push_back({1e4, -1e4});
    pts.push_back({0, 1e4});
    std::vector<std::array<int, 3>> tris{{n, n + 1, n + 2}};
    for (int p = 0; p < n; ++p) {
        std::map<std::pair<int, int>, int> edgeUse;  // directed edges of the cavity
        std::vector<std::array<int, 3>> kept;
        for (const auto& t : tris) {
            if (inCircumcircle(pts[t[0]], pts[t[1]], pts[t[2]], pts[p])) {
                for (int e = 0; e < 3; ++e) {
                    int a = t[e], b = t[(e + 1) % 3];
                    auto reverse = edgeUse.find({b, a});
                    if (reverse != edgeUse.end())
                        edgeUse.erase(reverse);  // shared by two removed triangles
                    else
                        edgeUse[{a, b}] = 1;
                }
            } else {
                kept.push_back(t);
            }
        }
        for (const auto& [edge, use] : edgeUse)
            if (cross(pts[edge.first], pts[edge.second], pts[p]) > kAreaEpsilon)
                kept.push_back({edge.first, edge.second, p});
        tris = std::move(kept);
    }
    std::map<std::pair<int, int>, int> edgeCount;
    for (const auto& t : tris) {
        if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
        if (cross(pts[t[0]], pts[t[1]], pts[t[2]]) <= kAreaEpsilon) continue;
        m_triangles.push_back(t);
        for (int e = 0; e < 3; ++e) {
            int a = t[e], b = t[(e + 1) % 3];
            ++edgeCount[{std::min(a, b), std::max(a, b)}];
        }
    }
    for (const auto& [edge, count] : edgeCount)
        if (count == 1) m_boundary.push_back({edge.first, edge.second});
}

Weights Triangulation::weightsAt(DiskPoint p) const {
    for (const auto& t : m_triangles) {
        DiskPoint a = m_points[t[0]], b = m_points[t[1]], c = m_points[t[2]];
        double area = cross(a, b, c);
        double wa = cross(b, c, p) / area, wb = cross(c, a, p) / area, wc = cross(a, b, p) / area;
        const double eps = -1e-12;
        if (wa >= eps && wb >= eps && wc >= eps) {
            wa = std::max(wa, 0.0);
            wb = std::max(wb, 0.0);
            wc = std::max(wc, 0.0);
            double sum = wa + wb + wc;
            Weights w;
            w.index = {t[0], t[1], t[2]};
            w.weight = {wa / sum, wb / sum, wc / sum};
            w.count = 3;
            w.inside = true;
            return w;
        }
    }
    return nearestOnBoundary(p);
}

Weights Triangulation::nearestOnBoundary(DiskPoint p) const {
    Weights w;
    double best = std::numeric_limits<double>::infinity();
    if (m_boundary.empty()) {  // a single point
        w.inside = std::hypot(p.x - m_points[0].x, p.y - m_points[0].y) < 1e-9;
        return w;
    }
    for (const auto& e : m_boundary) {
        auto [t, d2] = closestOnSegment(m_points[e[0]], m_points[e[1]], p);
        if (d2 < best) {
            best = d2;
            w.index = {e[0], e[1], e[0]};
            w.weight = {1 - t, t, 0};
            w.count = 2;
        }
    }
    // On the data itself (a collinear set, or exactly on a hull edge) counts as inside.
    w.inside = best < 1e-18;
    return w;
}

}  // namespace btflut
