#include "core/direction/direction.h"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace btflut {

namespace {
double wrapAzimuth(double phi) {
    double wrapped = std::fmod(phi, 2 * std::numbers::pi);
    return wrapped < 0 ? wrapped + 2 * std::numbers::pi : wrapped;
}

std::string formatVector(Vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

// A number as people write it: 95, 1.0021, 2 (not 95.000000).
std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}
}  // namespace

Direction Direction::fromDegrees(double thetaDeg, double phiDeg) {
    return {thetaDeg * kDegree, wrapAzimuth(phiDeg * kDegree)};
}

Vec3 toVector(Direction d) {
    double s = std::sin(d.theta);
    return {s * std::cos(d.phi), s * std::sin(d.phi), std::cos(d.theta)};
}

std::optional<Vec3> normalized(Vec3 v) {
    const double scale = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(scale > 0) || !std::isfinite(scale)) return std::nullopt;
    v = {v.x / scale, v.y / scale, v.z / scale};
    const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return Vec3{v.x / length, v.y / length, v.z / length};
}

Direction fromVector(Vec3 v) {
    BTFLUT_DCHECK(v.x != 0 || v.y != 0 || v.z != 0);
    // atan2 keeps full precision near the pole, where acos(z) loses half the digits.
    double phi = (v.x == 0 && v.y == 0) ? 0.0 : std::atan2(v.y, v.x);
    return {std::atan2(std::hypot(v.x, v.y), v.z), wrapAzimuth(phi)};
}

DiskPoint toDisk(Direction d) {
    double r = std::numbers::sqrt2 * std::sin(0.5 * d.theta);
    return {r * std::cos(d.phi), r * std::sin(d.phi)};
}

Direction fromDisk(DiskPoint p) {
    double r = std::min(1.0, std::hypot(p.x, p.y));
    double phi = (p.x == 0 && p.y == 0) ? 0.0 : std::atan2(p.y, p.x);
    return {2 * std::asin(r / std::numbers::sqrt2), wrapAzimuth(phi)};
}

DiskPoint diskGridPoint(int i, int j, int size) {
    const double step = 2.0 / (size - 1);
    return {-1 + step * i, -1 + step * j};
}

double angleBetween(Direction a, Direction b) {
    Vec3 u = toVector(a), v = toVector(b);
    // atan2 of |u x v| and u.v stays accurate for tiny and near-opposite angles.
    Vec3 c{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    return std::atan2(std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z), u.x * v.x + u.y * v.y + u.z * v.z);
}

Result<Direction> directionFromMeasuredVector(Vec3 v, const std::string& what, double lengthTolerance) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        return Error{what + ": direction " + formatVector(v) + " is not a finite vector"};
    double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (std::abs(len - 1) > lengthTolerance)
        return Error{what + ": direction " + formatVector(v) + " is not a unit vector (length " + formatNumber(len) +
                     ", more than " + formatNumber(lengthTolerance * 100) + "% from 1)"};
    if (v.z / len <= 1e-9) return Error{what + ": direction " + formatVector(v) + " is at or below the horizon"};
    return fromVector(v);
}

Result<Direction> directionFromDegrees(double thetaDeg, double phiDeg, const std::string& what) {
    if (!std::isfinite(thetaDeg) || !std::isfinite(phiDeg)) return Error{what + ": angle is not a finite number"};
    if (thetaDeg < 0 || thetaDeg >= 90)
        return Error{what + ": theta " + formatNumber(thetaDeg) +
                     " degrees is outside [0, 90) (90 and beyond is at or below the horizon)"};
    return Direction::fromDegrees(thetaDeg, phiDeg);
}

Result<Direction> parseDirection(const std::string& text, const std::string& what) {
    double values[2];
    const char* p = text.data();
    const char* end = text.data() + text.size();
    for (int i = 0; i < 2; ++i) {
        while (p < end && *p == ' ') ++p;
        auto [next, ec] = std::from_chars(p, end, values[i]);
        if (ec != std::errc{}) return Error{what + ": expected THETA,PHI in degrees, got '" + text + "'"};
        p = next;
        while (p < end && *p == ' ') ++p;
        if (i == 0) {
            if (p == end || *p != ',') return Error{what + ": expected THETA,PHI in degrees, got '" + text + "'"};
            ++p;
        }
    }
    if (p != end) return Error{what + ": expected THETA,PHI in degrees, got '" + text + "'"};
    return directionFromDegrees(values[0], values[1], what);
}

GridCell gridCellAt(DiskPoint p, int size) {
    const double last = size - 1;
    const double gx = std::clamp((p.x + 1) / 2 * last, 0.0, last), gy = std::clamp((p.y + 1) / 2 * last, 0.0, last);
    const int i = std::min(static_cast<int>(gx), size - 2), j = std::min(static_cast<int>(gy), size - 2);
    const double fx = gx - i, fy = gy - j;
    const auto at = [&](int di, int dj) { return static_cast<std::size_t>((j + dj) * size + i + di); };
    return {{at(0, 0), at(1, 0), at(0, 1), at(1, 1)}, {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy}};
}

}  // namespace btflut
