#pragma once
// Bidirectional grey-level histograms of a Gaussian rough surface (paper section 5).
//
//   SurfaceModel concrete{.roughness = 0.4};
//   std::vector<double> h = simulateHistogram(concrete, light, view, {.method = ...});
//
// Methods, each a normalised histogram over [0, 1] (bin 0 also holds shadowed points):
//   mc-paper   the paper's six-step recipe as written: facets from eq. 3 that face the
//              camera, shadowed ones to bin 0 (self-shadowed, or by intersection with
//              probability 1 - P_ill), the rest binned by value. Step 3 (accept with the
//              masking probability P_vis(theta_r)) is a constant factor for all facets, so
//              it changes nothing but the rejection rate and is skipped (at grazing views
//              it would reject everything).
//   mc         the same with each facet weighted by the image area it covers,
//              (v . m) / m_z: what a camera's pixels actually sample.
//   quadrature the area-weighted recipe integrated deterministically over the slopes with
//              Gauss-Legendre rules split exactly at the visibility and self-shadowing
//              boundaries (no sampling noise; `nodes` per axis and piece).
//   quadrature-paper  the same for the paper's recipe.
// Monte Carlo runs in blocks of 4096 points, each with its own seeded generator, on all
// cores; results do not depend on the thread count.

#include <cstdint>
#include <string>
#include <vector>

#include "core/physics/surface.h"

namespace btflut {

enum class SimulationMethod { McPaper, Mc, Quadrature, QuadraturePaper };

Result<SimulationMethod> parseSimulationMethod(const std::string& name);
const char* simulationMethodName(SimulationMethod m);

struct SimulationOptions {
    SimulationMethod method = SimulationMethod::Quadrature;
    int bins = 64;
    std::uint64_t samples = 50000;  ///< Monte Carlo points binned
    std::uint64_t seed = 1;
    int nodes = 64;     ///< quadrature nodes per axis and piece
    double smooth = 0;  ///< Gaussian smoothing width in bins (0: none)
    int threads = 0;    ///< 0: all cores
};

/// The normalised histogram (options.bins bins, sums to 1) for one light and view direction
/// (theta in [0, 90] degrees, 90 included). The model must be valid (validateModel).
std::vector<double> simulateHistogram(const SurfaceModel& model, Direction light, Direction view,
                                      const SimulationOptions& options);

/// simulateHistogram as masses per code, what matchLut and quantileFunction take (lut.h): bin b
/// covers [b, b + 1) / bins, the cell of code b + 1 on a bins + 1 code scale (code 0 empty).
std::vector<double> simulateMass(const SurfaceModel& model, Direction light, Direction view,
                                 const SimulationOptions& options);

/// Gaussian smoothing with a width of `width` bins; mass is kept (the kernel is renormalised
/// where it meets the ends).
std::vector<double> smoothHistogram(const std::vector<double>& h, double width);

/// E_P[max(0, v . m) / m_z] over the slope distribution of rms slope r, by the quadrature.
/// The white-furnace identity says it equals cos(theta_v) (1 + Lambda(r, theta_v)).
double projectedVisibleArea(double r, double thetaV, int nodes = 64);

/// The same by Monte Carlo with n samples: the mean and its standard error.
struct Estimate {
    double mean;
    double standardError;
};
Estimate projectedVisibleAreaMc(double r, Direction view, std::uint64_t n, std::uint64_t seed);

}  // namespace btflut
