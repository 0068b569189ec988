#include "core/physics/geometry.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "core/data/dataset.h"

namespace btflut {

namespace {
// A signed angle in the x-z plane (positive towards +x) as a direction.
Direction inPlane(double degrees) { return Direction::fromDegrees(std::abs(degrees), degrees >= 0 ? 0 : 180); }
}  // namespace

std::vector<Geometry> curetC2() {
    std::vector<Geometry> g;
    for (int k = 1; k <= 11; ++k) {
        const double normal = (k - 4) * 11.25;
        // Lab frame: light at in-plane angle 0, camera at 45; relative to the normal they sit
        // at -normal and 45 - normal.
        g.push_back({"c2-" + std::to_string(k), inPlane(-normal), inPlane(45 - normal)});
    }
    return g;
}

std::vector<Geometry> curetSpecular() {
    std::vector<Geometry> g;
    for (int k = 1; k <= 7; ++k) g.push_back({"s" + std::to_string(k), inPlane(-11.25 * k), inPlane(11.25 * k)});
    return g;
}

std::vector<Geometry> rtiDome(int lights) {
    std::vector<Geometry> g;
    const double zMin = std::cos(75 * kDegree), golden = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int k = 0; k < lights; ++k) {
        // Equal solid angle per light: z evenly spaced from 1 down to cos(75 degrees).
        const double z = 1 - (k + 0.5) / lights * (1 - zMin);
        g.push_back({"l" + std::to_string(k + 1), Direction{std::acos(z), std::fmod(k * golden, 2 * std::numbers::pi)},
                     Direction{}});
    }
    return g;
}

std::vector<Geometry> btfDome(int n) {
    const std::vector<Geometry> dome = rtiDome(n);
    std::vector<Geometry> g;
    char name[32];
    for (int v = 0; v < n; ++v)
        for (int l = 0; l < n; ++l) {
            std::snprintf(name, sizeof name, "v%02d-l%02d", v + 1, l + 1);
            g.push_back({name, dome[static_cast<std::size_t>(l)].light, dome[static_cast<std::size_t>(v)].light});
        }
    return g;
}

Result<std::vector<Geometry>> parseGeometry(const std::string& spec) {
    if (spec == "curet-c2") return curetC2();
    if (spec == "curet-specular") return curetSpecular();
    if (spec.rfind("rti-", 0) == 0) {
        char* end = nullptr;
        const long n = std::strtol(spec.c_str() + 4, &end, 10);
        if (*end != '\0' || n < 1 || n > 10000)
            return Error{"--geometry " + spec + ": expected rti-N with N in 1..10000"};
        return rtiDome(static_cast<int>(n));
    }
    if (spec.rfind("btf-", 0) == 0) {
        char* end = nullptr;
        const long n = std::strtol(spec.c_str() + 4, &end, 10);
        if (*end != '\0' || n < 1 || n > 100)
            return Error{"--geometry " + spec + ": expected btf-N with N in 1..100 (N views x N lights)"};
        return btfDome(static_cast<int>(n));
    }
    if (spec.find(',') != std::string::npos && spec.find('/') == std::string::npos) {
        std::vector<Geometry> g;
        std::istringstream in(spec);
        std::string item;
        while (std::getline(in, item, ';')) {
            double a[4];
            char sep[3];
            std::istringstream fields(item);
            if (!(fields >> a[0] >> sep[0] >> a[1] >> sep[1] >> a[2] >> sep[2] >> a[3]) || sep[0] != ',' ||
                sep[1] != ',' || sep[2] != ',' || !(fields >> std::ws).eof())
                return Error{"--geometry: expected THETA_I,PHI_I,THETA_R,PHI_R[;...], got '" + item + "'"};
            for (double v : a)
                if (!std::isfinite(v)) return Error{"--geometry: '" + item + "' has a non-finite angle"};
            if (a[0] < 0 || a[0] > 90 || a[2] < 0 || a[2] > 90)
                return Error{"--geometry: '" + item + "': theta must be within [0, 90] degrees"};
            g.push_back({"p" + std::to_string(g.size() + 1), Direction::fromDegrees(a[0], a[1]),
                         Direction::fromDegrees(a[2], a[3])});
        }
        if (g.empty()) return Error{"--geometry: empty list"};
        return g;
    }
    Result<Dataset> ds = openDataset(spec);
    if (!ds)
        return Error{"--geometry '" + spec + "' is not curet-c2, curet-specular, rti-N, btf-N, a list or a dataset (" +
                     ds.error() + ")"};
    std::vector<Geometry> g;
    for (const DatasetImage& im : ds->images) g.push_back({im.name, im.light, im.view});
    return g;
}

}  // namespace btflut
