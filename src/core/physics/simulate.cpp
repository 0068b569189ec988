#include "core/physics/simulate.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

#include "core/parallel.h"
#include "core/random.h"

namespace btflut {

namespace {

constexpr double kSlopeRange = 8;  // slopes beyond 8 r carry < 1.3e-15 of the mass
constexpr std::uint64_t kBlock = 4096;

// ---- Gauss-Legendre rules -------------------------------------------------------------

struct Rule {
    std::vector<double> x, w;  // on [-1, 1]
};

Rule computeRule(int n) {
    Rule rule;
    rule.x.resize(static_cast<std::size_t>(n));
    rule.w.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) p0 = 1, p1 = x;
            dp = n * (x * p1 - p0) / (x * x - 1);
            double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        rule.x[static_cast<std::size_t>(i)] = x;
        rule.w[static_cast<std::size_t>(i)] = 2 / ((1 - x * x) * dp * dp);
    }
    return rule;
}

const Rule& gaussLegendre(int n) {
    static std::mutex mutex;
    static std::map<int, Rule> cache;
    std::lock_guard lock(mutex);
    auto it = cache.find(n);
    if (it == cache.end()) it = cache.emplace(n, computeRule(n)).first;
    return it->second;
}

double normalDensity(double x, double sd) {
    return std::exp(-0.5 * (x / sd) * (x / sd)) / (sd * std::sqrt(2 * std::numbers::pi));
}

// Standard normal CDF and its inverse (Acklam's rational approximation, relative error
// below 1.2e-9: ample for placing nodes, whose weights are exact in probability).
double normalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

double normalQuantile(double u) {
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                               1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                               6.680131188771972e+01, -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                               -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    double x;
    if (u < 0.02425) {
        const double q = std::sqrt(-2 * std::log(u));
        x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    } else if (u > 1 - 0.02425) {
        const double q = std::sqrt(-2 * std::log(1 - u));
        x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    } else {
        const double q = u - 0.5, t = q * q;
        x = (((((a[0] * t + a[1]) * t + a[2]) * t + a[3]) * t + a[4]) * t + a[5]) * q /
            (((((b[0] * t + b[1]) * t + b[2]) * t + b[3]) * t + b[4]) * t + 1);
    }
    return x;
}

// cot(theta) for theta in [0, pi/2]: +inf at 0, 0 at the horizon.
double cotangent(double theta) {
    if (theta <= 0) return std::numeric_limits<double>::infinity();
    if (theta >= std::numbers::pi / 2) return 0;
    return 1 / std::tan(theta);
}

// Pieces of [lo, hi] cut at the given points.
std::vector<std::pair<double, double>> pieces(double lo, double hi, std::initializer_list<double> cuts) {
    std::vector<double> points{lo};
    for (double c : cuts)
        if (c > lo && c < hi) points.push_back(c);
    points.push_back(hi);
    std::sort(points.begin(), points.end());
    std::vector<std::pair<double, double>> out;
    for (std::size_t i = 1; i < points.size(); ++i)
        if (points[i] > points[i - 1]) out.push_back({points[i - 1], points[i]});
    return out;
}

// Spreads `mass` over the bins as the distribution of value + X + Y with X, Y uniform on
// [-x, x] and [-y, y]: a linear function over a rectangular cell. Values below 0 count in
// bin 0, values at or above 1 in the last bin (the camera clips).
void spreadOverBins(std::vector<double>& h, double value, double x, double y, double mass) {
    const int bins = static_cast<int>(h.size());
    if (x < y) std::swap(x, y);
    // CDF of the sum at s, using H, the antiderivative of clamp(t, 0, 1).
    auto cdf = [x, y](double s) {
        // Exactly 0 and 1 outside the support: there the closed form would subtract nearly
        // equal large numbers (s / x can be 1e12 for a tiny cell) and lose mass.
        if (s <= -x - y) return 0.0;
        if (s >= x + y) return 1.0;
        auto clamp01 = [](double t) { return std::clamp(t, 0.0, 1.0); };
        // When y << x the closed form below also cancels (it divides by y); the uniform CDF
        // is then exact to O((y / x)^2).
        if (y <= 1e-4 * x) return clamp01((s + x) / (2 * x));
        auto H = [](double t) { return t <= 0 ? 0.0 : t < 1 ? 0.5 * t * t : t - 0.5; };
        return clamp01(x / y * (H((s + y + x) / (2 * x)) - H((s - y + x) / (2 * x))));
    };
    const double lo = value - x - y, hi = value + x + y;
    const int first = std::clamp(static_cast<int>(std::floor(lo * bins)), 0, bins - 1);
    const int last = std::clamp(static_cast<int>(std::floor(hi * bins)), 0, bins - 1);
    double below = 0;  // CDF at the lower edge of the current bin (-inf for bin 0)
    for (int b = first; b <= last; ++b) {
        const double above = b == bins - 1 ? 1.0 : cdf(static_cast<double>(b + 1) / bins - value);
        h[static_cast<std::size_t>(b)] += mass * (above - below);
        below = above;
    }
}

int binOf(double value, int bins) { return std::clamp(static_cast<int>(value * bins), 0, bins - 1); }

Vec3 facetNormal(double p, double q) {
    const double len = std::sqrt(1 + p * p + q * q);
    return {-p / len, -q / len, 1 / len};
}

std::uint64_t blockSeed(std::uint64_t seed, std::uint64_t block) {
    return seed * 0x9e3779b97f4a7c15ull + block * 0xd1b54a32d192ed03ull + 1;
}

// ---- The two histogram integrators ------------------------------------------------------

std::vector<double> monteCarlo(const SurfaceModel& model, Direction light, Direction view, const SimulationOptions& o,
                               bool areaWeighted) {
    const Vec3 l = toVector(light), v = toVector(view);
    const double pIll = smithUnoccluded(model.roughness, light.theta);
    const std::uint64_t blocks = (o.samples + kBlock - 1) / kBlock;
    std::vector<std::vector<double>> perBlock(blocks);
    parallelFor(blocks, o.threads, [&](std::size_t b) {
        // Accumulate locally: neighbouring blocks' vectors share cache lines.
        std::vector<double> h(static_cast<std::size_t>(o.bins), 0.0);
        Random random(blockSeed(o.seed, b));
        const std::uint64_t points = std::min(kBlock, o.samples - b * kBlock);
        for (std::uint64_t n = 0; n < points;) {
            auto [zp, zq] = random.normals();
            const double p = model.roughness * zp, q = model.roughness * zq;
            // Steps 1-2: a facet from eq. 3, accepted when it faces the camera. Its image
            // area per unit macro area is (v . m) / m_z = v_z - p v_x - q v_y.
            const double area = v.z - p * v.x - q * v.y;
            if (area <= 0) continue;
            ++n;
            const double weight = areaWeighted ? area : 1.0;
            const Vec3 m = facetNormal(p, q);
            const double lit = l.z - p * l.x - q * l.y;
            // Steps 4-5: self-shadowed, or shadowed by intersection, go to bin 0.
            if (lit <= 0 || random.uniform() >= pIll) {
                h[0] += weight;
                continue;
            }
            // Step 6: the facet's value.
            h[static_cast<std::size_t>(binOf(facetValue(model, m, l, v), o.bins))] += weight;
        }
        perBlock[b] = std::move(h);
    });
    std::vector<double> h(static_cast<std::size_t>(o.bins), 0.0);
    for (const auto& block : perBlock)
        for (std::size_t i = 0; i < h.size(); ++i) h[i] += block[i];
    return h;
}

std::vector<double> quadrature(const SurfaceModel& model, Direction light, Direction view, const SimulationOptions& o,
                               bool areaWeighted) {
    const Vec3 l = toVector(light), v = toVector(view);
    const double r = model.roughness;
    const double pIll = smithUnoccluded(r, light.theta);
    // Slopes in view-aligned axes: a along the view's azimuth, b across it. The facet faces
    // the camera iff a < cot(theta_v); it faces the light iff a cos(d) + b sin(d) < cot(theta_i)
    // with d the light's azimuth relative to the view's.
    const double aVisible = cotangent(view.theta);
    const double tLight = cotangent(light.theta);
    const double d = light.phi - view.phi, cosD = std::cos(d), sinD = std::sin(d);
    const bool inPlane = std::abs(sinD) < 1e-9;
    const double aLight = inPlane ? tLight / cosD : std::numeric_limits<double>::quiet_NaN();
    const double cosV = std::cos(view.phi), sinV = std::sin(view.phi);

    // The camera's (clipped) value: a cell saturated throughout must stay in the top bin.
    auto valueAt = [&](double a, double b) {
        const double p = a * cosV - b * sinV, q = a * sinV + b * cosV;
        return facetValue(model, facetNormal(p, q), l, v);
    };
    // A node stands for a cell around it, [a0, a1] x [b0, b1] within its piece: its mass
    // spreads over the values the cell covers, estimated from secants across the cell
    // (exact for a linear value; bounded by the real values across a narrow specular lobe).
    // Dropping it into one bin aliases the node grid against the bin edges.
    auto add = [&](std::vector<double>& h, double a, double b, double a0, double a1, double b0, double b1,
                   double weight) {
        const double p = a * cosV - b * sinV, q = a * sinV + b * cosV;
        if (l.z - p * l.x - q * l.y <= 0) {  // self-shadowed
            h[0] += weight;
            return;
        }
        h[0] += weight * (1 - pIll);
        const double value = valueAt(a, b);
        const double spreadA = 0.5 * std::abs(valueAt(a1, b) - valueAt(a0, b));
        const double spreadB = 0.5 * std::abs(valueAt(a, b1) - valueAt(a, b0));
        spreadOverBins(h, value, spreadA, spreadB, weight * pIll);
    };
    // Both slope axes are integrated in probability, u = Phi(slope / r), with Gauss-Legendre
    // rules, so nodes sit where the mass is and the Gaussian density cancels. Pieces are cut
    // at the visibility and shadowing boundaries, so no integrand has a kink. Each node
    // stands for the cell of its probability share around it (kept within its piece).
    auto uOf = [r](double slope) { return std::isfinite(slope) ? normalCdf(slope / r) : (slope > 0 ? 1.0 : 0.0); };
    const double tail = kSlopeRange * r;  // bounds of the outermost cells
    auto slopeOf = [r, tail](double u) {
        return u <= 0 ? -tail : u >= 1 ? tail : std::clamp(r * normalQuantile(u), -tail, tail);
    };
    const Rule& rule = gaussLegendre(o.nodes);
    const std::size_t n = rule.x.size();
    // The node, its weight and its cell's slope bounds for rule node k on [u0, u1].
    struct Node {
        double slope, weight, lo, hi;
    };
    auto node = [&](double u0, double u1, std::size_t k) {
        const double half = 0.5 * (u1 - u0), u = u0 + half * (1 + rule.x[k]), w = half * rule.w[k];
        return Node{slopeOf(u), w, slopeOf(std::max(u0, u - 0.5 * w)), slopeOf(std::min(u1, u + 0.5 * w))};
    };
    const auto aPieces = pieces(0, uOf(aVisible), {inPlane ? uOf(aLight) : -1.0});
    std::vector<Node> uncut;  // the b-nodes of rows that no shadow boundary crosses
    for (std::size_t k = 0; k < n; ++k) uncut.push_back(node(0, 1, k));
    std::vector<std::vector<double>> rows(aPieces.size() * n);
    // Threads only pay off beyond about a millisecond of work.
    const int threads = rows.size() * n < 4096 ? 1 : o.threads;
    parallelFor(rows.size(), threads, [&](std::size_t row) {
        std::vector<double> h(static_cast<std::size_t>(o.bins), 0.0);
        const Node a = node(aPieces[row / n].first, aPieces[row / n].second, row % n);
        double wa = a.weight;
        if (areaWeighted) wa *= v.z - std::sin(view.theta) * a.slope;
        if (wa > 0) {
            const double bCut = inPlane ? -1.0 : uOf((tLight - a.slope * cosD) / sinD);
            const auto bPieces = pieces(0, 1, {bCut});
            for (auto [w0, w1] : bPieces)
                for (std::size_t k = 0; k < n; ++k) {
                    const Node b = bPieces.size() == 1 ? uncut[k] : node(w0, w1, k);
                    add(h, a.slope, b.slope, a.lo, a.hi, b.lo, b.hi, wa * b.weight);
                }
        }
        rows[row] = std::move(h);
    });
    std::vector<double> h(static_cast<std::size_t>(o.bins), 0.0);
    for (const auto& row : rows)
        for (std::size_t k = 0; k < h.size(); ++k) h[k] += row[k];
    return h;
}

}  // namespace

Result<SimulationMethod> parseSimulationMethod(const std::string& name) {
    for (SimulationMethod m : {SimulationMethod::McPaper, SimulationMethod::Mc, SimulationMethod::Quadrature,
                               SimulationMethod::QuadraturePaper})
        if (name == simulationMethodName(m)) return m;
    return Error{"--method '" + name + "' is not mc, mc-paper, quadrature or quadrature-paper"};
}

const char* simulationMethodName(SimulationMethod m) {
    switch (m) {
        case SimulationMethod::McPaper:
            return "mc-paper";
        case SimulationMethod::Mc:
            return "mc";
        case SimulationMethod::Quadrature:
            return "quadrature";
        case SimulationMethod::QuadraturePaper:
            return "quadrature-paper";
    }
    return "?";
}

std::vector<double> simulateMass(const SurfaceModel& model, Direction light, Direction view,
                                 const SimulationOptions& options) {
    const std::vector<double> histogram = simulateHistogram(model, light, view, options);
    std::vector<double> mass(histogram.size() + 1, 0.0);
    std::copy(histogram.begin(), histogram.end(), mass.begin() + 1);
    return mass;
}

std::vector<double> smoothHistogram(const std::vector<double>& h, double width) {
    if (width <= 0) return h;
    const int n = static_cast<int>(h.size());
    // Four widths, but never past the histogram (a huge width would overflow an int).
    const int reach = static_cast<int>(std::min(std::ceil(4 * width), static_cast<double>(n)));
    std::vector<double> out(h.size(), 0.0);
    for (int i = 0; i < n; ++i) {
        if (h[static_cast<std::size_t>(i)] == 0) continue;
        const int lo = std::max(0, i - reach), hi = std::min(n - 1, i + reach);
        double norm = 0;
        for (int j = lo; j <= hi; ++j) norm += std::exp(-0.5 * (j - i) * (j - i) / (width * width));
        for (int j = lo; j <= hi; ++j)
            out[static_cast<std::size_t>(j)] +=
                h[static_cast<std::size_t>(i)] * std::exp(-0.5 * (j - i) * (j - i) / (width * width)) / norm;
    }
    return out;
}

std::vector<double> simulateHistogram(const SurfaceModel& model, Direction light, Direction view,
                                      const SimulationOptions& o) {
    BTFLUT_CHECK(o.bins >= 2 && o.nodes >= 1);
    std::vector<double> h;
    switch (o.method) {
        case SimulationMethod::McPaper:
            h = monteCarlo(model, light, view, o, false);
            break;
        case SimulationMethod::Mc:
            h = monteCarlo(model, light, view, o, true);
            break;
        case SimulationMethod::Quadrature:
            h = quadrature(model, light, view, o, true);
            break;
        case SimulationMethod::QuadraturePaper:
            h = quadrature(model, light, view, o, false);
            break;
    }
    double total = 0;
    for (double v : h) total += v;
    if (total > 0 && std::isfinite(total))
        for (double& v : h) v /= total;
    else  // nothing visible can only happen in degenerate limits: call it black
        std::fill(h.begin(), h.end(), 0.0), h[0] = 1;
    h = smoothHistogram(h, o.smooth);
    // Renormalise exactly once more: sums are compared against 1 to 1e-12.
    total = 0;
    for (double v : h) total += v;
    for (double& v : h) v /= total;
    return h;
}

double projectedVisibleArea(double r, double thetaV, int nodes) {
    const double range = kSlopeRange * r, c = std::cos(thetaV), s = std::sin(thetaV);
    const Rule& rule = gaussLegendre(nodes);
    double sum = 0;
    for (auto [a0, a1] : pieces(-range, std::min(range, cotangent(thetaV)), {})) {
        for (std::size_t i = 0; i < rule.x.size(); ++i) {
            const double a = 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * rule.x[i];
            sum += 0.5 * (a1 - a0) * rule.w[i] * normalDensity(a, r) * (c - s * a);
        }
    }
    return sum;
}

Estimate projectedVisibleAreaMc(double r, Direction view, std::uint64_t n, std::uint64_t seed) {
    const Vec3 v = toVector(view);
    Random random(blockSeed(seed, 0));
    double sum = 0, sum2 = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
        auto [zp, zq] = random.normals();
        const double area = std::max(0.0, v.z - r * zp * v.x - r * zq * v.y);
        sum += area;
        sum2 += area * area;
    }
    const double mean = sum / static_cast<double>(n);
    const double variance = std::max(0.0, sum2 / static_cast<double>(n) - mean * mean);
    return {mean, std::sqrt(variance / static_cast<double>(n))};
}

}  // namespace btflut
