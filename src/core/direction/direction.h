#pragma once
// Directions on the upper hemisphere of the sample frame (DESIGN.md): z is the macroscopic
// normal, x image right, y image up. theta is the polar angle from z, phi the azimuth from x
// towards y. Radians inside the code; degrees in files and flags.
//
// Directions are laid out for interpolation on the Lambert azimuthal equal-area disk:
// r = sqrt(2) sin(theta / 2), (x, y) = r (cos phi, sin phi). The pole is the centre (no
// singularity), the horizon the unit circle, and equal areas of the disk are equal solid
// angles, so a regular grid on it samples the hemisphere evenly.

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "core/result.h"

namespace btflut {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Vec3 {
    double x = 0, y = 0, z = 0;
};

struct DiskPoint {
    double x = 0, y = 0;
};

struct Direction {
    double theta = 0;  ///< polar angle from the normal, radians, [0, pi/2]
    double phi = 0;    ///< azimuth from x towards y, radians, [0, 2 pi)

    static Direction fromDegrees(double thetaDeg, double phiDeg);
    double thetaDegrees() const { return theta / kDegree; }
    double phiDegrees() const { return phi / kDegree; }
};

/// Unit vector of a direction.
Vec3 toVector(Direction d);

/// The unit vector along v, or nothing when v is zero or not finite. Safe for any finite
/// v (no overflow or underflow in the length: v is scaled by its largest component first).
std::optional<Vec3> normalized(Vec3 v);

/// Direction of a vector. The vector must be finite and non-zero (it is normalised).
Direction fromVector(Vec3 v);

/// Equal-area disk coordinates of a direction (unit disk for the upper hemisphere).
DiskPoint toDisk(Direction d);

/// Inverse of toDisk; points outside the unit disk are pulled onto the horizon.
Direction fromDisk(DiskPoint p);

/// Node (i, j) of a size x size grid over the square around the disk: x = -1 + 2 i / (size - 1),
/// y likewise with j (the corners lie beyond the horizon).
DiskPoint diskGridPoint(int i, int j, int size);
/// The cell of that grid around a disk point (clamped to the grid), for bilinear reads of
/// node values: its four nodes (j * size + i: (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1))
/// and their weights.
struct GridCell {
    std::array<std::size_t, 4> node{};
    std::array<double, 4> weight{};
};
GridCell gridCellAt(DiskPoint p, int size);

/// Great-circle angle between two directions, radians.
double angleBetween(Direction a, Direction b);

/// A light or view direction from a measured unit vector (z towards the camera / normal).
/// Refuses NaN, vectors whose length is off 1 by more than `lengthTolerance` (they are
/// renormalised otherwise) and directions at or below the horizon. `what` names the source in
/// the error.
Result<Direction> directionFromMeasuredVector(Vec3 v, const std::string& what, double lengthTolerance = 1e-3);

/// How far the light vectors of RTI and photometric-stereo files may be from unit length:
/// other tools round them (0.21 -0.24 0.95 is 1.0021 long); within 2% they are normalised.
constexpr double kRoundedLightTolerance = 0.02;

/// A direction from degrees as written in files and flags: theta in [0, 90) (the horizon
/// itself is refused, nothing is lit or seen from there), phi any finite value.
Result<Direction> directionFromDegrees(double thetaDeg, double phiDeg, const std::string& what);

/// Parses "THETA,PHI" in degrees (command-line form), validated as directionFromDegrees.
Result<Direction> parseDirection(const std::string& text, const std::string& what);

}  // namespace btflut
