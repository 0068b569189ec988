// Delaunay simplices from Qhull (Debian's libqhull_r, the reentrant library): the only file
// that sees Qhull's C macros.
#include <cstdio>

#include "core/direction/triangulation.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wpedantic"
extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace btflut {

namespace {

// One Qhull run; false when Qhull reports an error (precision problems on degenerate input).
bool runQhull(int dimension, std::vector<double> coordinates, const char* options,
              std::vector<std::array<int, 4>>& simplices) {
    qhT context;
    qhT* qh = &context;
    // Qhull prints its errors; they are not the user's business (the caller retries or reports).
    std::FILE* quiet = std::fopen("/dev/null", "w");
    qh_zero(qh, quiet);
    const int points = static_cast<int>(coordinates.size()) / dimension;
    std::string flags = std::string("qhull d ") + options;
    const int status = qh_new_qhull(qh, dimension, points, coordinates.data(), False, flags.data(), nullptr, quiet);
    if (status == 0) {
        facetT* facet;
        vertexT *vertex, **vertexp;
        FORALLfacets {
            if (facet->upperdelaunay) continue;
            std::array<int, 4> simplex{-1, -1, -1, -1};
            int k = 0;
            FOREACHvertex_(facet->vertices) {
                if (k <= dimension) simplex[static_cast<std::size_t>(k)] = qh_pointid(qh, vertex->point);
                ++k;
            }
            if (k == dimension + 1) simplices.push_back(simplex);
        }
    }
    qh_freeqhull(qh, !qh_ALL);
    int stillLong = 0, totalLong = 0;
    qh_memfreeshort(qh, &stillLong, &totalLong);
    if (quiet) std::fclose(quiet);
    return status == 0;
}

}  // namespace

std::vector<std::array<int, 4>> delaunaySimplices(int dimension, const std::vector<double>& coordinates) {
    BTFLUT_CHECK(dimension == 2 || dimension == 3);
    std::vector<std::array<int, 4>> simplices;
    // Triangulated output (Qt) of the lower hull, scaled to the unit box (Qbb); Qz adds a
    // point at infinity for the many cospherical points of regular light domes. Should
    // that still meet a precision error, joggled input (QJ) always succeeds.
    if (runQhull(dimension, coordinates, "Qt Qbb Qc Qz Q12", simplices)) return simplices;
    simplices.clear();
    runQhull(dimension, coordinates, "QJ Qbb Qc Q12", simplices);
    return simplices;
}

}  // namespace btflut
#pragma GCC diagnostic pop
