#pragma once
// Interpolation weights over scattered directions: Delaunay triangulations (Qhull) of their
// equal-area disk points (direction.h), and of points in 3-D for banks interpolated over
// (theta_i, theta_r, phi_i - phi_r) (lut_bank.h). Inside the triangulation a query gets the
// barycentric weights of its simplex; outside, the weights of the nearest point on the
// boundary (clamping, so the result is continuous and never extrapolates beyond the data).
// Degenerate sets degrade: one or two points, or collinear points, to the nearest point /
// the nearest point on their polyline; coplanar points in 3-D to a triangulation of their
// plane. Building takes O(n log n) (Qhull), a query O(1) on average (a bucket grid).
//
//   Triangulation tri({toDisk(a), toDisk(b), toDisk(c)});
//   Weights w = tri.weightsAt(toDisk(query));   // w.index[i], w.weight[i], i < w.count

#include <array>
#include <vector>

#include "core/direction/direction.h"

namespace btflut {

struct Weights {
    std::array<int, 4> index{0, 0, 0, 0};
    std::array<double, 4> weight{1, 0, 0, 0};
    int count = 1;        ///< number of points used (1 to 4)
    bool inside = false;  ///< within the data's hull (interpolation, not clamping)
};

/// Points (of any dimension up to 3) sorted into a uniform grid of cells, each listing the
/// simplices whose bounding box meets it: point location in O(1) on average.
struct SimplexBuckets {
    int dimension = 2;
    int cellsPerSide = 0;  ///< 0: nothing registered
    std::array<double, 3> low{}, cellSize{};
    std::vector<int> start;  ///< per cell, into `simplices` (one past the end: next cell's start)
    std::vector<int> simplices;

    /// Registers simplices (their vertex indices, dimension + 1 each) of `points` (dimension
    /// coordinates each, interleaved).
    void build(int dimension, const std::vector<double>& points, const std::vector<std::array<int, 4>>& simplices);
    /// The simplices registered in the cell of a point; empty outside the grid.
    std::pair<const int*, const int*> near(const double* point) const;
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
    std::vector<std::array<int, 3>> m_triangles;  // counter-clockwise
    std::vector<std::array<int, 2>> m_boundary;   // hull edges (or the polyline)
    SimplexBuckets m_buckets;
};

struct Point3 {
    double x = 0, y = 0, z = 0;
};

/// The same in three dimensions: tetrahedra inside the hull, the nearest point on a hull
/// face outside. Points that span only a plane or a line are triangulated there, and a
/// query is first projected onto it (off it counts as outside).
class Triangulation3 {
public:
    Triangulation3() = default;
    /// Points must be distinct; at least one.
    explicit Triangulation3(std::vector<Point3> points);

    Weights weightsAt(Point3 p) const;

    const std::vector<Point3>& points() const { return m_points; }
    /// 3 for a set that spans space, 2 for a plane, 1 for a line, 0 for one point.
    int span() const { return m_span; }

private:
    Weights nearestOnBoundary(Point3 p) const;

    std::vector<Point3> m_points;
    int m_span = 0;
    // span 3:
    std::vector<std::array<int, 4>> m_tetrahedra;
    std::vector<std::array<int, 3>> m_boundary;  // hull faces
    SimplexBuckets m_buckets;
    // span < 3: the points in coordinates (u, v) of their plane or line through m_origin
    Point3 m_origin, m_axisU, m_axisV;
    Triangulation m_flat;
};

/// Delaunay simplices of points in `dimension` = 2 or 3 (coordinates interleaved), each as
/// dimension + 1 point indices (unused slots -1). The points must span the space. Qhull.
std::vector<std::array<int, 4>> delaunaySimplices(int dimension, const std::vector<double>& coordinates);

/// True when two of the points lie within `tolerance` (> 0, finite) of each other. O(n log n).
bool hasNearDuplicates(const std::vector<DiskPoint>& points, double tolerance);

}  // namespace btflut
