#pragma once
// A smooth estimate of a layer's targets between its measured lights (issue 34). The blend of
// the measured quantile functions over the light triangulation (lut_bank.h) follows only the
// three nodes around a light; a low-degree polynomial in the light vector, ridge-fitted to
// every node, follows how the whole set moves (a shadow's growth towards the horizon). The
// bank adds the fit's difference from the blend of the fit at those three nodes:
//
//   target(L) = sum_n w_n(L) q_n + fit(L) - sum_n w_n(L) fit(L_n)
//
// so a measured light keeps its measured target exactly (w is 1 at its node), and between
// lights the blend's residual from the fit is interpolated. Clamping each quantile function
// afterwards to the range of the nodes blended and sorting it (the monotone rearrangement)
// keep it a distribution within the measurements' levels.
// The degree and the ridge weight are chosen per region by validation on the measured lights
// (bake/target_choice.h).
//
//   TargetFit fit = fitTargets(lights, nodeValues, layout, {{.degree = 3, .ridge = 1e-4}});
//   std::vector<double> t = fitTerms(light, fit.degree);     // what lookups weigh

#include <cstddef>
#include <vector>

#include "core/direction/direction.h"
#include "core/direction/triangulation.h"

namespace btflut {

/// The polynomial's terms other than the constant (which the difference above cancels): the
/// monomials x^a y^b z^c of the light vector with c <= 1 (z^2 = 1 - x^2 - y^2) and
/// a + b + c <= degree, by total degree, so a lower degree's terms lead a higher one's.
/// (degree + 1)^2 - 1 of them: the span of the spherical harmonics up to that degree.
int fitTermCount(int degree);
std::vector<double> fitTerms(Direction light, int degree);

/// The isotropic domain's (lut_bank.h): the monomials x^a y^b z^c of a pair's point
/// (isotropicPoint: the light's disk point turned to the view's azimuth, and the view's disk
/// radius) with 1 <= a + b + c <= degree, by total degree: (degree + 3 choose 3) - 1 of them.
int pairTermCount(int degree);
std::vector<double> pairTerms(Point3 q, int degree);

/// The largest degree a file may hold (docs/btflut-format.md, TFIT).
constexpr int kMaxFitDegree = 8;

/// Where a fit's terms are read: a layer's light vector, or the isotropic domain's point.
enum class FitDomain { Light, Pair };

/// A layer's fit (or, in the isotropic domain, the bank's over every pair): coefficients of
/// each term for each of the node values (regions x channels x quantiles); zero for a region
/// that keeps the blend alone. Empty (degree 0): no fit.
struct TargetFit {
    int degree = 0;
    std::vector<float> coefficients;  ///< termCount() x values, term-major
    FitDomain domain = FitDomain::Light;

    bool empty() const { return degree == 0; }
    int termCount() const { return domain == FitDomain::Light ? fitTermCount(degree) : pairTermCount(degree); }
};

/// One region's estimator: the blend alone (degree 0) or a polynomial of `degree` fitted with
/// ridge weight `ridge` (per node, on the terms of the unit light vector).
struct FitChoice {
    int degree = 0;
    double ridge = 0;
};

/// Fits `values` (lights.size() x length, node-major; each region one run of
/// length / choices.size() values) with each region's choice. Lights must be distinct.
TargetFit fitTargets(const std::vector<Direction>& lights, const float* values, std::size_t length,
                     const std::vector<FitChoice>& choices);

/// The same over pairs' points (the isotropic domain): a FitDomain::Pair fit.
TargetFit fitPairTargets(const std::vector<Point3>& points, const float* values, std::size_t length,
                         const std::vector<FitChoice>& choices);

/// wa a + wb b: the two corrections mixed (the lower degree's terms lead the higher's, so its
/// coefficients are padded with zeros). Both fit the same values.
TargetFit mixFits(const TargetFit& a, double wa, const TargetFit& b, double wb);

/// Adds weight x the fit's difference from the blend of the fit at the nodes (w, their
/// lights) to `sum` (length values): the correction a lookup makes at `light`.
void addFitCorrection(const TargetFit& fit, Direction light, const std::vector<Direction>& nodeLights,
                      const std::vector<double>& nodeWeights, double weight, std::vector<double>& sum);

/// The range a correction may move a lookup's values within: per run of `segment` values, the
/// lowest and highest of the nodes it blends. The measurements keep their levels: a shadow the
/// fitted model adds falls at the capture's black level (camera floor, ambient light), which
/// the model lacks, not below it (the bundled material's held-out target 0.2435 -> 0.1794).
struct SegmentRanges {
    std::vector<float> low, high;

    /// Widens each run's range to hold `values` (length values, runs of `segment`).
    void include(const float* values, std::size_t length, std::size_t segment);
};

/// The same in the isotropic domain: the fit read at `q`, its nodes at their points.
void addPairFitCorrection(const TargetFit& fit, Point3 q, const std::vector<Point3>& nodePoints,
                          const std::vector<double>& nodeWeights, double weight, std::vector<double>& sum);

/// Each run of `segment` values clamped to its range and sorted: quantile functions again.
/// A range's ends are the edges of its darkest and brightest code's cells (a code y's values
/// lie in (y - 1, y], lut.h), where the dithered output rounds a tie: a shelf of clamped values
/// there would render on either side, so the values outside go to those cells' centres, half
/// a `code` in (0 and 1 stay: black stays black). Values within the range stay as they are.
void makeQuantileFunctions(std::vector<float>& values, std::size_t segment, const SegmentRanges& ranges, float code);

}  // namespace btflut
