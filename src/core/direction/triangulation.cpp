#include "core/direction/triangulation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

#include "core/check.h"

namespace btflut {

namespace {

double cross(DiskPoint o, DiskPoint a, DiskPoint b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Closest point to p on segment ab, as the parameter t in [0, 1] and the squared distance.
std::pair<double, double> closestOnSegment(DiskPoint a, DiskPoint b, DiskPoint p) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0;
    double qx = a.x + t * dx - p.x, qy = a.y + t * dy - p.y;
    return {t, qx * qx + qy * qy};
}

constexpr double kAreaEpsilon = 1e-12;
constexpr double kInsideEpsilon = -1e-12;  // barycentric weights this far below 0 still count as inside

using V3 = Eigen::Vector3d;
V3 vec(Point3 p) { return {p.x, p.y, p.z}; }

// Barycentric weights of the point of triangle abc closest to p (Ericson, Real-Time
// Collision Detection, 5.1.5), and the squared distance.
std::pair<std::array<double, 3>, double> closestOnTriangle(const V3& a, const V3& b, const V3& c, const V3& p) {
    const V3 ab = b - a, ac = c - a, ap = p - a;
    auto result = [&](double u, double v, double w) {
        const V3 q = u * a + v * b + w * c;
        return std::pair{std::array<double, 3>{u, v, w}, (q - p).squaredNorm()};
    };
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return result(1, 0, 0);
    const V3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return result(0, 1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return result(1 - v, v, 0);
    }
    const V3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return result(0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return result(1 - w, 0, w);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return result(0, 1 - w, w);
    }
    const double denom = 1 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    return result(1 - v - w, v, w);
}

// Weights of `count` points with non-negative barycentric coordinates, normalised.
Weights simplexWeights(const int* index, const double* coordinates, int count, bool inside) {
    Weights w;
    double sum = 0;
    for (int k = 0; k < count; ++k) sum += std::max(coordinates[k], 0.0);
    for (int k = 0; k < count; ++k) {
        w.index[static_cast<std::size_t>(k)] = index[k];
        w.weight[static_cast<std::size_t>(k)] = std::max(coordinates[k], 0.0) / sum;
    }
    w.count = count;
    w.inside = inside;
    return w;
}

}  // namespace

void SimplexBuckets::build(int dim, const std::vector<double>& points, const std::vector<std::array<int, 4>>& list) {
    dimension = dim;
    const std::size_t n = points.size() / static_cast<std::size_t>(dim);
    if (list.empty() || n == 0) return;
    std::array<double, 3> high{};
    for (int d = 0; d < dim; ++d) {
        low[d] = std::numeric_limits<double>::infinity();
        high[d] = -low[d];
        for (std::size_t i = 0; i < n; ++i) {
            low[d] = std::min(low[d], points[i * dim + d]);
            high[d] = std::max(high[d], points[i * dim + d]);
        }
    }
    // About one simplex per cell.
    cellsPerSide = std::max(1, static_cast<int>(std::ceil(std::pow(static_cast<double>(list.size()), 1.0 / dim))));
    for (int d = 0; d < dim; ++d) cellSize[d] = std::max(high[d] - low[d], 1e-300) / cellsPerSide;
    std::size_t cells = 1;
    for (int d = 0; d < dim; ++d) cells *= static_cast<std::size_t>(cellsPerSide);
    // Each simplex's range of cells (its bounding box, grown by a hair so that points on
    // a cell border find it from both sides).
    auto cellRange = [&](const std::array<int, 4>& s, int d) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k <= dim; ++k) {
            lo = std::min(lo, points[static_cast<std::size_t>(s[static_cast<std::size_t>(k)]) * dim + d]);
            hi = std::max(hi, points[static_cast<std::size_t>(s[static_cast<std::size_t>(k)]) * dim + d]);
        }
        const double slack = 1e-9 * cellSize[d];
        auto cell = [&](double v) {
            return std::clamp(static_cast<int>(std::floor((v - low[d]) / cellSize[d])), 0, cellsPerSide - 1);
        };
        return std::pair{cell(lo - slack), cell(hi + slack)};
    };
    auto forEachCell = [&](const std::array<int, 4>& s, auto&& visit) {
        std::array<std::pair<int, int>, 3> r{};
        for (int d = 0; d < 3; ++d) r[d] = d < dim ? cellRange(s, d) : std::pair{0, 0};
        for (int z = r[2].first; z <= r[2].second; ++z)
            for (int y = r[1].first; y <= r[1].second; ++y)
                for (int x = r[0].first; x <= r[0].second; ++x)
                    visit((static_cast<std::size_t>(z) * cellsPerSide + y) * cellsPerSide + x);
    };
    start.assign(cells + 1, 0);
    for (const auto& s : list) forEachCell(s, [&](std::size_t c) { ++start[c + 1]; });
    for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
    simplices.assign(static_cast<std::size_t>(start[cells]), 0);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < list.size(); ++i)
        forEachCell(list[i],
                    [&](std::size_t c) { simplices[static_cast<std::size_t>(fill[c]++)] = static_cast<int>(i); });
}

std::pair<const int*, const int*> SimplexBuckets::near(const double* p) const {
    if (cellsPerSide == 0) return {nullptr, nullptr};
    std::size_t cell = 0;
    for (int d = dimension - 1; d >= 0; --d) {
        const double at = (p[d] - low[d]) / cellSize[d];
        // Outside the points' box is outside their hull (a hair of slack at its faces).
        if (!(at >= -1e-9 && at <= cellsPerSide + 1e-9)) return {nullptr, nullptr};
        cell = cell * static_cast<std::size_t>(cellsPerSide) +
               static_cast<std::size_t>(std::clamp(static_cast<int>(at), 0, cellsPerSide - 1));
    }
    return {simplices.data() + start[cell], simplices.data() + start[cell + 1]};
}

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

    std::vector<double> coordinates;
    for (const DiskPoint& p : m_points) coordinates.insert(coordinates.end(), {p.x, p.y});
    std::vector<std::array<int, 4>> kept;
    std::map<std::pair<int, int>, int> edgeCount;
    for (std::array<int, 4> t : delaunaySimplices(2, coordinates)) {
        double area = cross(m_points[t[0]], m_points[t[1]], m_points[t[2]]);
        if (area < 0) std::swap(t[1], t[2]), area = -area;  // counter-clockwise
        if (area <= kAreaEpsilon) continue;                 // a sliver of cocircular points
        m_triangles.push_back({t[0], t[1], t[2]});
        kept.push_back(t);
        for (int e = 0; e < 3; ++e) {
            int a = t[e], b = t[(e + 1) % 3];
            ++edgeCount[{std::min(a, b), std::max(a, b)}];
        }
    }
    for (const auto& [edge, count] : edgeCount)
        if (count == 1) m_boundary.push_back({edge.first, edge.second});
    m_buckets.build(2, coordinates, kept);
}

Weights Triangulation::weightsAt(DiskPoint p) const {
    const double query[2] = {p.x, p.y};
    for (auto [it, end] = m_buckets.near(query); it != end; ++it) {
        const auto& t = m_triangles[static_cast<std::size_t>(*it)];
        DiskPoint a = m_points[t[0]], b = m_points[t[1]], c = m_points[t[2]];
        double area = cross(a, b, c);
        const double w[3] = {cross(b, c, p) / area, cross(c, a, p) / area, cross(a, b, p) / area};
        if (w[0] >= kInsideEpsilon && w[1] >= kInsideEpsilon && w[2] >= kInsideEpsilon)
            return simplexWeights(t.data(), w, 3, true);
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
            w.index = {e[0], e[1], e[0], e[0]};
            w.weight = {1 - t, t, 0, 0};
            w.count = 2;
        }
    }
    // On the data itself (a collinear set, or exactly on a hull edge) counts as inside.
    w.inside = best < 1e-18;
    return w;
}

Triangulation3::Triangulation3(std::vector<Point3> points) : m_points(std::move(points)) {
    BTFLUT_CHECK(!m_points.empty());
    const auto n = static_cast<Eigen::Index>(m_points.size());
    // The affine span, from the singular values of the centred points.
    V3 centre = V3::Zero();
    for (const Point3& p : m_points) centre += vec(p);
    centre /= static_cast<double>(n);
    Eigen::MatrixXd centred(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        centred.row(i) = (vec(m_points[static_cast<std::size_t>(i)]) - centre).transpose();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
    const Eigen::Vector3d sigma = svd.singularValues();
    constexpr double kFlat = 1e-7;  // coordinates are O(1)
    m_span = static_cast<int>((sigma.array() > kFlat * std::sqrt(static_cast<double>(n))).count());
    m_origin = {centre.x(), centre.y(), centre.z()};

    if (m_span < 3) {
        const V3 u = svd.matrixV().col(0), v = svd.matrixV().col(1);
        m_axisU = {u.x(), u.y(), u.z()};
        m_axisV = m_span >= 2 ? Point3{v.x(), v.y(), v.z()} : Point3{};
        std::vector<DiskPoint> flat;
        for (const Point3& p : m_points) {
            const V3 d = vec(p) - centre;
            flat.push_back({d.dot(vec(m_axisU)), d.dot(vec(m_axisV))});
        }
        m_flat = Triangulation(std::move(flat));
        return;
    }
    std::vector<double> coordinates;
    for (const Point3& p : m_points) coordinates.insert(coordinates.end(), {p.x, p.y, p.z});
    std::map<std::array<int, 3>, int> faceCount;
    for (const std::array<int, 4>& t : delaunaySimplices(3, coordinates)) {
        const V3 a = vec(m_points[t[0]]), b = vec(m_points[t[1]]), c = vec(m_points[t[2]]), d = vec(m_points[t[3]]);
        if (std::abs((b - a).cross(c - a).dot(d - a)) <= kAreaEpsilon) continue;  // a flat sliver
        m_tetrahedra.push_back(t);
        for (int skip = 0; skip < 4; ++skip) {
            std::array<int, 3> face{};
            for (int k = 0, j = 0; k < 4; ++k)
                if (k != skip) face[static_cast<std::size_t>(j++)] = t[static_cast<std::size_t>(k)];
            std::sort(face.begin(), face.end());
            ++faceCount[face];
        }
    }
    for (const auto& [face, count] : faceCount)
        if (count == 1) m_boundary.push_back(face);
    m_buckets.build(3, coordinates, m_tetrahedra);
}

Weights Triangulation3::weightsAt(Point3 p) const {
    if (m_span < 3) {
        const V3 d = vec(p) - vec(m_origin);
        const double u = d.dot(vec(m_axisU)), v = d.dot(vec(m_axisV));
        Weights w = m_flat.weightsAt({u, v});
        const double off = (d - u * vec(m_axisU) - v * vec(m_axisV)).norm();
        w.inside = w.inside && off < 1e-9;
        return w;
    }
    const double query[3] = {p.x, p.y, p.z};
    const V3 q = vec(p);
    for (auto [it, end] = m_buckets.near(query); it != end; ++it) {
        const auto& t = m_tetrahedra[static_cast<std::size_t>(*it)];
        Eigen::Matrix3d m;
        const V3 a = vec(m_points[t[0]]);
        for (int k = 0; k < 3; ++k) m.col(k) = vec(m_points[t[static_cast<std::size_t>(k + 1)]]) - a;
        const V3 bcd = m.partialPivLu().solve(q - a);
        const double w[4] = {1 - bcd.sum(), bcd.x(), bcd.y(), bcd.z()};
        if (w[0] >= kInsideEpsilon && w[1] >= kInsideEpsilon && w[2] >= kInsideEpsilon && w[3] >= kInsideEpsilon)
            return simplexWeights(t.data(), w, 4, true);
    }
    return nearestOnBoundary(p);
}

Weights Triangulation3::nearestOnBoundary(Point3 p) const {
    double best = std::numeric_limits<double>::infinity();
    Weights w;
    for (const auto& f : m_boundary) {
        auto [coordinates, d2] =
            closestOnTriangle(vec(m_points[f[0]]), vec(m_points[f[1]]), vec(m_points[f[2]]), vec(p));
        if (d2 < best) {
            best = d2;
            w = simplexWeights(f.data(), coordinates.data(), 3, false);
        }
    }
    w.inside = best < 1e-18;
    return w;
}

bool hasNearDuplicates(const std::vector<DiskPoint>& points, double tolerance) {
    // Cells of side `tolerance`: a point's near neighbours are in its own and the 8 cells
    // around it, so each point meets O(1) others whatever the layout.
    auto cellOf = [&](double v) { return static_cast<std::int64_t>(std::floor(v / tolerance)); };
    std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> cells;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::int64_t cx = cellOf(points[i].x), cy = cellOf(points[i].y);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                auto it = cells.find({cx + dx, cy + dy});
                if (it == cells.end()) continue;
                for (std::size_t j : it->second)
                    if (std::hypot(points[j].x - points[i].x, points[j].y - points[i].y) <= tolerance) return true;
            }
        cells[{cx, cy}].push_back(i);
    }
    return false;
}

}  // namespace btflut
