#pragma once
// Fitting the rough-surface model to measured bidirectional histograms (paper section 6.1,
// which fitted by hand): non-linear least squares (Ceres Solver) of the model's parameters to
// every histogram at once. Residuals are the bin differences between the model's histogram
// (the deterministic quadrature, simulate.h) and the measured one, for every direction.
//
//   Result<SurfaceFit> fit = fitSurfaceModel(rows, FitBrdf::Lambert);
//   fit->model; fit->smoothing; fit->parameters[k].standardError;
//
// Parameters per BRDF: lambert r, gain, smoothing; ts r, gain, sigma, ior, smoothing; mix r,
// gain, ks, sigma, ior, smoothing (kd 1: only the ratio of ks to kd and the gain are seen).
// The smoothing is the Gaussian width in bins that stands for the camera's noise and blur.
//
// Smooth in its parameters: the quadrature integrates over fixed Gauss-Legendre nodes whose
// positions move continuously with r (split exactly at the shadowing and masking
// boundaries), and bins by the exact fraction of each integration cell's value range inside
// each bin, so a histogram changes continuously, not in jumps as sampled facets crossing a
// bin edge would; central differences then give the solver its Jacobian.
// Start values: the best point of a coarse grid over r and the gain (sigma too for ts/mix),
// never asked of the user. Standard errors: from the Jacobian at the optimum (Ceres'
// covariance), scaled by the residual variance.

#include <string>
#include <vector>

#include "core/histogram/histogram.h"
#include "core/physics/model_bank.h"
#include "core/physics/simulate.h"

namespace btflut {

enum class FitBrdf { Lambert, TorranceSparrow, Mix };
Result<FitBrdf> parseFitBrdf(const std::string& name);
const char* fitBrdfName(FitBrdf brdf);

struct FitParameter {
    std::string name;
    double value = 0;
    double standardError = 0;  ///< NaN: the data do not determine it (the Jacobian's null space)
    bool determined() const { return standardError == standardError; }
};

struct SurfaceFit {
    SurfaceModel model;
    double smoothing = 0;                  ///< Gaussian width in bins
    std::vector<FitParameter> parameters;  ///< in the order above
    std::vector<double> residuals;         ///< per direction: RMS of its bin differences
    double rms = 0;                        ///< over every bin of every direction
    int iterations = 0;
    double seconds = 0;
    int nodes = 0;  ///< the quadrature's, as fitted
};

struct FitOptions {
    int nodes = 32;  ///< quadrature nodes per axis and piece while fitting
    int maxIterations = 100;
    bool standardErrors = true;  ///< false: NaN, sparing the covariance (a fit used only for its model)
};

/// Fits the model; errors: fewer directions than parameters, histograms of different bin
/// counts, directions below the horizon, a fit that does not converge.
Result<SurfaceFit> fitSurfaceModel(const std::vector<HistogramRow>& measured, FitBrdf brdf,
                                   const FitOptions& options = {});

/// The fitted model as bank parameters (bake --model, --fill model): the smoothing, fitted
/// in the histograms' `bins`, rescaled to the bins the bank is simulated at.
ModelBankParams fittedModelParams(const SurfaceFit& fit, std::size_t bins);

/// The fitted model's histogram for one row's directions, as the fit compared it.
std::vector<double> fittedHistogram(const SurfaceFit& fit, const HistogramRow& row);

}  // namespace btflut
