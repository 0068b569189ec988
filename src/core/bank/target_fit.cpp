#include "core/bank/target_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace btflut {

int fitTermCount(int degree) { return (degree + 1) * (degree + 1) - 1; }

std::vector<double> fitTerms(Direction light, int degree) {
    const Vec3 v = toVector(light);
    std::vector<double> terms;
    terms.reserve(static_cast<std::size_t>(fitTermCount(degree)));
    for (int total = 1; total <= degree; ++total)
        for (int c = 0; c <= 1 && c <= total; ++c)
            for (int a = total - c; a >= 0; --a) {
                const int b = total - c - a;
                terms.push_back(std::pow(v.x, a) * std::pow(v.y, b) * (c ? v.z : 1.0));
            }
    return terms;
}

int pairTermCount(int degree) { return (degree + 1) * (degree + 2) * (degree + 3) / 6 - 1; }

std::vector<double> pairTerms(Point3 q, int degree) {
    std::vector<double> terms;
    terms.reserve(static_cast<std::size_t>(pairTermCount(degree)));
    for (int total = 1; total <= degree; ++total)
        for (int a = total; a >= 0; --a)
            for (int b = total - a; b >= 0; --b)
                terms.push_back(std::pow(q.x, a) * std::pow(q.y, b) * std::pow(q.z, total - a - b));
    return terms;
}

namespace {

int largestDegree(const std::vector<FitChoice>& choices) {
    int degree = 0;
    for (const FitChoice& c : choices) degree = std::max(degree, c.degree);
    return degree;
}

// Ridge least squares of each region's run of `values` on the terms at each node (`terms`:
// every node's at the largest degree; a lower degree's are their first termCount).
TargetFit fitOnTerms(FitDomain domain, const std::vector<std::vector<double>>& terms, const float* values,
                     std::size_t length, const std::vector<FitChoice>& choices) {
    BTFLUT_CHECK(!choices.empty() && length % choices.size() == 0);
    TargetFit fit{.degree = largestDegree(choices), .domain = domain};
    if (fit.degree == 0) return fit;
    const auto nodes = static_cast<Eigen::Index>(terms.size());
    const std::size_t run = length / choices.size();
    fit.coefficients.assign(static_cast<std::size_t>(fit.termCount()) * length, 0.f);
    for (std::size_t r = 0; r < choices.size(); ++r) {
        const FitChoice& choice = choices[r];
        if (choice.degree == 0) continue;
        const Eigen::Index count = TargetFit{choice.degree, {}, domain}.termCount();
        Eigen::MatrixXd f(nodes, count);
        for (Eigen::Index n = 0; n < nodes; ++n)
            for (Eigen::Index k = 0; k < count; ++k)
                f(n, k) = terms[static_cast<std::size_t>(n)][static_cast<std::size_t>(k)];
        Eigen::MatrixXd q(nodes, static_cast<Eigen::Index>(run));
        for (Eigen::Index n = 0; n < nodes; ++n)
            for (std::size_t k = 0; k < run; ++k)
                q(n, static_cast<Eigen::Index>(k)) = values[static_cast<std::size_t>(n) * length + r * run + k];
        // Centred, so the unpenalised constant (which lookups cancel) absorbs the mean.
        f.rowwise() -= f.colwise().mean();
        q.rowwise() -= q.colwise().mean();
        Eigen::MatrixXd normal = f.transpose() * f;
        normal.diagonal().array() += choice.ridge * static_cast<double>(nodes);
        const Eigen::MatrixXd c = normal.ldlt().solve(f.transpose() * q);
        for (Eigen::Index t = 0; t < count; ++t)
            for (std::size_t k = 0; k < run; ++k)
                fit.coefficients[static_cast<std::size_t>(t) * length + r * run + k] =
                    static_cast<float>(c(t, static_cast<Eigen::Index>(k)));
    }
    return fit;
}

// Adds weight x (the terms at the lookup - the nodes' blend of theirs) . coefficients.
void addTermCorrection(const TargetFit& fit, std::vector<double> difference,
                       const std::vector<std::vector<double>>& nodeTerms, const std::vector<double>& nodeWeights,
                       double weight, std::vector<double>& sum) {
    BTFLUT_CHECK(nodeTerms.size() == nodeWeights.size());
    for (std::size_t n = 0; n < nodeTerms.size(); ++n)
        for (std::size_t t = 0; t < difference.size(); ++t) difference[t] -= nodeWeights[n] * nodeTerms[n][t];
    const std::size_t length = sum.size();
    BTFLUT_CHECK(fit.coefficients.size() == difference.size() * length);
    for (std::size_t t = 0; t < difference.size(); ++t) {
        const double d = weight * difference[t];
        if (d == 0) continue;
        const float* c = &fit.coefficients[t * length];
        for (std::size_t k = 0; k < length; ++k) sum[k] += d * c[k];
    }
}

}  // namespace

TargetFit fitTargets(const std::vector<Direction>& lights, const float* values, std::size_t length,
                     const std::vector<FitChoice>& choices) {
    std::vector<std::vector<double>> terms;
    for (const Direction& l : lights) terms.push_back(fitTerms(l, largestDegree(choices)));
    return fitOnTerms(FitDomain::Light, terms, values, length, choices);
}

TargetFit fitPairTargets(const std::vector<Point3>& points, const float* values, std::size_t length,
                         const std::vector<FitChoice>& choices) {
    std::vector<std::vector<double>> terms;
    for (const Point3& q : points) terms.push_back(pairTerms(q, largestDegree(choices)));
    return fitOnTerms(FitDomain::Pair, terms, values, length, choices);
}

TargetFit mixFits(const TargetFit& a, double wa, const TargetFit& b, double wb) {
    if (a.empty() || b.empty()) {
        TargetFit out = a.empty() ? b : a;
        for (float& c : out.coefficients) c *= static_cast<float>(a.empty() ? wb : wa);
        return out;
    }
    BTFLUT_CHECK(a.domain == b.domain);
    const std::size_t length = a.coefficients.size() / static_cast<std::size_t>(a.termCount());
    BTFLUT_CHECK(b.coefficients.size() == static_cast<std::size_t>(b.termCount()) * length);
    TargetFit out{std::max(a.degree, b.degree), {}, a.domain};
    out.coefficients.assign(static_cast<std::size_t>(out.termCount()) * length, 0.f);
    for (const auto& [fit, w] : {std::pair{&a, wa}, std::pair{&b, wb}})
        for (std::size_t k = 0; k < fit->coefficients.size(); ++k)
            out.coefficients[k] += static_cast<float>(w) * fit->coefficients[k];
    return out;
}

void addFitCorrection(const TargetFit& fit, Direction light, const std::vector<Direction>& nodeLights,
                      const std::vector<double>& nodeWeights, double weight, std::vector<double>& sum) {
    if (fit.empty() || weight == 0) return;
    BTFLUT_CHECK(fit.domain == FitDomain::Light);
    std::vector<std::vector<double>> nodeTerms;
    for (const Direction& l : nodeLights) nodeTerms.push_back(fitTerms(l, fit.degree));
    addTermCorrection(fit, fitTerms(light, fit.degree), nodeTerms, nodeWeights, weight, sum);
}

void addPairFitCorrection(const TargetFit& fit, Point3 q, const std::vector<Point3>& nodePoints,
                          const std::vector<double>& nodeWeights, double weight, std::vector<double>& sum) {
    if (fit.empty() || weight == 0) return;
    BTFLUT_CHECK(fit.domain == FitDomain::Pair);
    std::vector<std::vector<double>> nodeTerms;
    for (const Point3& p : nodePoints) nodeTerms.push_back(pairTerms(p, fit.degree));
    addTermCorrection(fit, pairTerms(q, fit.degree), nodeTerms, nodeWeights, weight, sum);
}

void SegmentRanges::include(const float* values, std::size_t length, std::size_t segment) {
    BTFLUT_CHECK(segment > 0 && length % segment == 0);
    const std::size_t runs = length / segment;
    if (low.empty()) {
        low.assign(runs, 1.f);
        high.assign(runs, 0.f);
    }
    BTFLUT_CHECK(low.size() == runs);
    for (std::size_t r = 0; r < runs; ++r) {
        const auto [lo, hi] = std::minmax_element(values + r * segment, values + (r + 1) * segment);
        low[r] = std::min(low[r], *lo);
        high[r] = std::max(high[r], *hi);
    }
}

void makeQuantileFunctions(std::vector<float>& values, std::size_t segment, const SegmentRanges& ranges, float code) {
    BTFLUT_CHECK(segment > 0 && values.size() % segment == 0 && ranges.low.size() == values.size() / segment);
    const float half = std::isfinite(code) && code > 0 ? code / 2 : 0.f;
    for (std::size_t r = 0, at = 0; at < values.size(); ++r, at += segment) {
        const auto first = values.begin() + static_cast<std::ptrdiff_t>(at);
        const auto last = first + static_cast<std::ptrdiff_t>(segment);
        const float low = std::clamp(ranges.low[r], 0.f, 1.f), high = std::clamp(ranges.high[r], low, 1.f);
        // Where the clamped values go: inside the range, so a measured light's own values stay.
        const float below = low > 0 ? std::min(low + half, high) : 0.f;
        const float above = high < 1 ? std::max(high - half, low) : 1.f;
        for (auto v = first; v != last; ++v) *v = *v < low ? below : *v > high ? above : *v;
        std::sort(first, last);
    }
}

}  // namespace btflut
