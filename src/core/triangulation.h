#pragma once
// Interpolation weights over scattered directions: a Delaunay triangulation of their
// equal-area disk points (direction.h). Inside the triangulation a query gets the
// barycentric weights of its triangle; outside, the weights of the nearest point on the
// boundary (clamping, so the result is continuous and never extrapolates beyond the data).
// One or two points, or collinear points, degrade to nearest point / the nearest point
// on their polyline.
//
//   Triangulation tri({toDisk(a), toDisk(b), toDisk(c)});
//   Weights w = tri.weightsAt(toDisk(query));   // w.index[i], w.weight[i], i < w.count

#include <array>
#include <vector>

#include "core/direction.h"

namespace btflut {

struct Weights {
    std::array<int, 3> index{0, 0, 0};
    std::array<double, 3> weight{1, 0, 0};
    int count = 1;        ///< number of points used (1 to 3)
    bool inside = false;  ///< within the data's hull (interpolation, not clamping)
};

class Triangulation {
public:
    Triangulation() = default;
    /// Points must be distinct (callers merge duplicates first); at least one.
    explicit Triangulation(std::vector<DiskPoint> points);

    Weights weightsAt(DiskPoint p) const;

    const std::vector<DiskPoint>& points() const { return m_points; }
    const std::vector<std::array<int, 3>>& triangles() const { return m_triangles; }

private:
    Weights nearestOnBoundary(DiskPoint p) const;

    std::vector<DiskPoint> m_points;
    std::vector<std::array<int, 3>> m_triangles;           // counter-clockwise
    std::vector<std::array<int, 2>> m_boundary;            // hull edges (or the polyline)
};

}  // namespace btflut
