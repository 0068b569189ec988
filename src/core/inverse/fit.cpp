#include "core/inverse/fit.h"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace btflut {

namespace {

std::vector<std::string> parameterNames(FitBrdf brdf) {
    switch (brdf) {
        case FitBrdf::Lambert:
            return {"roughness", "gain", "smoothing"};
        case FitBrdf::TorranceSparrow:
            return {"roughness", "gain", "sigma", "ior", "smoothing"};
        case FitBrdf::Mix:
            return {"roughness", "gain", "ks", "sigma", "ior", "smoothing"};
    }
    return {};
}

// The model a parameter vector stands for. The solver's finite differences may step just
// outside the bounds, so every parameter is clamped into the model's domain here.
SurfaceModel modelOf(FitBrdf brdf, const double* p, double& smoothing) {
    SurfaceModel m;
    m.roughness = std::max(p[0], 1e-4);
    m.gain = std::max(p[1], 1e-6);
    switch (brdf) {
        case FitBrdf::Lambert:
            m.brdf = {.kd = 1, .ks = 0};
            smoothing = std::abs(p[2]);
            break;
        case FitBrdf::TorranceSparrow:
            m.brdf = {.kd = 0, .ks = 1, .sigma = std::max(p[2], 1e-3), .ior = std::max(p[3], 1.0)};
            smoothing = std::abs(p[4]);
            break;
        case FitBrdf::Mix:
            m.brdf = {.kd = 1, .ks = std::max(p[2], 0.0), .sigma = std::max(p[3], 1e-3), .ior = std::max(p[4], 1.0)};
            smoothing = std::abs(p[5]);
            break;
    }
    return m;
}

std::vector<double> simulated(const SurfaceModel& model, double smoothing, const HistogramRow& row, int nodes) {
    return simulateHistogram(model, row.light, row.view,
                             {.method = SimulationMethod::Quadrature,
                              .bins = static_cast<int>(row.bins.size()),
                              .nodes = nodes,
                              .smooth = smoothing,
                              .threads = 1});
}

// One direction's residuals: model bins minus measured bins.
struct DirectionResidual {
    FitBrdf brdf;
    const HistogramRow* row;
    int nodes;
    bool operator()(double const* const* parameters, double* residuals) const {
        double smoothing = 0;
        const SurfaceModel model = modelOf(brdf, parameters[0], smoothing);
        const std::vector<double> h = simulated(model, smoothing, *row, nodes);
        for (std::size_t k = 0; k < h.size(); ++k) residuals[k] = h[k] - row->bins[k];
        return true;
    }
};

// The sum of one direction's squared bin differences.
double squaredError(const SurfaceModel& model, double smoothing, const HistogramRow& row, int nodes) {
    const std::vector<double> h = simulated(model, smoothing, row, nodes);
    double sum = 0;
    for (std::size_t k = 0; k < h.size(); ++k) sum += (h[k] - row.bins[k]) * (h[k] - row.bins[k]);
    return sum;
}

double sumOfSquares(FitBrdf brdf, const std::vector<double>& p, const std::vector<HistogramRow>& rows, int nodes) {
    double smoothing = 0, sum = 0;
    const SurfaceModel model = modelOf(brdf, p.data(), smoothing);
    for (const HistogramRow& row : rows) sum += squaredError(model, smoothing, row, nodes);
    return sum;
}

// The best point of a coarse grid: the solver's start.
std::vector<double> startValues(FitBrdf brdf, const std::vector<HistogramRow>& rows) {
    std::vector<double> best;
    double bestCost = std::numeric_limits<double>::infinity();
    auto consider = [&](std::vector<double> p) {
        const double cost = sumOfSquares(brdf, p, rows, 6);
        if (cost < bestCost) {
            bestCost = cost;
            best = std::move(p);
        }
    };
    for (double r : {0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.1})
        for (double gain : {0.4, 0.7, 1.0, 1.5, 2.5}) switch (brdf) {
                case FitBrdf::Lambert:
                    consider({r, gain, 1.0});
                    break;
                case FitBrdf::TorranceSparrow:
                    for (double sigma : {0.1, 0.3}) consider({r, gain, sigma, 1.5, 1.0});
                    break;
                case FitBrdf::Mix:
                    for (double ks : {0.0, 0.2, 1.0})
                        for (double sigma : {0.1, 0.3}) consider({r, gain, ks, sigma, 1.5, 1.0});
                    break;
            }
    return best;
}

}  // namespace

Result<FitBrdf> parseFitBrdf(const std::string& name) {
    if (name == "lambert") return FitBrdf::Lambert;
    if (name == "ts") return FitBrdf::TorranceSparrow;
    if (name == "mix") return FitBrdf::Mix;
    return Error{"brdf '" + name + "' is not lambert, ts or mix"};
}

const char* fitBrdfName(FitBrdf brdf) {
    switch (brdf) {
        case FitBrdf::Lambert:
            return "lambert";
        case FitBrdf::TorranceSparrow:
            return "ts";
        case FitBrdf::Mix:
            return "mix";
    }
    return "";
}

Result<SurfaceFit> fitSurfaceModel(const std::vector<HistogramRow>& measured, FitBrdf brdf, const FitOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::string> names = parameterNames(brdf);
    if (measured.empty()) return Error{"no histograms to fit"};
    const std::size_t bins = measured.front().bins.size();
    std::size_t values = 0;
    for (const HistogramRow& row : measured) {
        if (row.bins.size() != bins)
            return Error{"histogram '" + row.name + "' has " + std::to_string(row.bins.size()) + " bins, '" +
                         measured.front().name + "' " + std::to_string(bins) + ": all must have the same"};
        for (const Direction& d : {row.light, row.view})
            if (!(d.theta >= 0 && d.theta <= M_PI / 2))
                return Error{"histogram '" + row.name + "': a direction below the horizon or not a number"};
        values += bins;
    }
    if (measured.size() < names.size())
        return Error{std::to_string(measured.size()) + " histogram(s) cannot determine the " +
                     std::to_string(names.size()) + " parameters of " + fitBrdfName(brdf) +
                     ": one direction per parameter at least"};

    std::vector<double> p = startValues(brdf, measured);
    ceres::Problem problem;
    for (const HistogramRow& row : measured) {
        auto* cost = new ceres::DynamicNumericDiffCostFunction<DirectionResidual, ceres::CENTRAL>(
            new DirectionResidual{brdf, &row, options.nodes});
        cost->AddParameterBlock(static_cast<int>(p.size()));
        cost->SetNumResiduals(static_cast<int>(bins));
        problem.AddResidualBlock(cost, nullptr, p.data());
    }
    problem.SetParameterLowerBound(p.data(), 0, 1e-3);                              // roughness
    problem.SetParameterLowerBound(p.data(), 1, 1e-4);                              // gain
    problem.SetParameterLowerBound(p.data(), static_cast<int>(p.size()) - 1, 0.0);  // smoothing
    if (brdf != FitBrdf::Lambert) {
        const int sigma = brdf == FitBrdf::Mix ? 3 : 2;
        problem.SetParameterLowerBound(p.data(), sigma, 1e-3);
        problem.SetParameterUpperBound(p.data(), sigma, 1.0);      // facet slopes beyond 45 degrees rms are no mirror
        problem.SetParameterLowerBound(p.data(), sigma + 1, 1.0);  // ior
        problem.SetParameterUpperBound(p.data(), sigma + 1, 4.0);
        if (brdf == FitBrdf::Mix) problem.SetParameterLowerBound(p.data(), 2, 0.0);  // ks
    }
    ceres::Solver::Options solverOptions;
    solverOptions.linear_solver_type = ceres::DENSE_QR;
    solverOptions.max_num_iterations = options.maxIterations;
    solverOptions.num_threads = 2;
    solverOptions.function_tolerance = 1e-6;  // Ceres' default: the quadrature's Jacobian is not exact to much less
    solverOptions.parameter_tolerance = 1e-8;
    solverOptions.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solverOptions, &problem, &summary);
    if (summary.termination_type != ceres::CONVERGENCE)
        return Error{"the fit did not converge (" + summary.message + ") after " +
                     std::to_string(summary.iterations.size()) + " iterations"};

    SurfaceFit fit;
    fit.model = modelOf(brdf, p.data(), fit.smoothing);
    fit.nodes = options.nodes;
    fit.iterations = static_cast<int>(summary.iterations.size());
    // Standard errors: the covariance of the parameters from the Jacobian at the optimum,
    // scaled by the residual variance (the solver's cost is half the sum of squares).
    const double variance = 2 * summary.final_cost / static_cast<double>(values - p.size());
    std::vector<double> covariance(p.size() * p.size(), std::numeric_limits<double>::quiet_NaN());
    ceres::Covariance::Options covarianceOptions;
    covarianceOptions.algorithm_type = ceres::DENSE_SVD;
    covarianceOptions.null_space_rank = -1;
    ceres::Covariance estimate(covarianceOptions);
    const std::vector<std::pair<const double*, const double*>> blocks{{p.data(), p.data()}};
    if (options.standardErrors && estimate.Compute(blocks, &problem))
        estimate.GetCovarianceBlock(p.data(), p.data(), covariance.data());
    for (std::size_t k = 0; k < p.size(); ++k) {
        const double error = std::sqrt(std::max(0.0, covariance[k * p.size() + k] * variance));
        // A direction the data do not constrain lies in the Jacobian's null space: no error.
        fit.parameters.push_back({names[k], k + 1 == p.size() ? std::abs(p[k]) : p[k], error > 0 ? error : NAN});
    }
    double total = 0;
    for (const HistogramRow& row : measured) {
        const double sum = squaredError(fit.model, fit.smoothing, row, options.nodes);
        fit.residuals.push_back(std::sqrt(sum / static_cast<double>(bins)));
        total += sum;
    }
    fit.rms = std::sqrt(total / static_cast<double>(values));
    fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return fit;
}

ModelBankParams fittedModelParams(const SurfaceFit& fit, std::size_t bins) {
    ModelBankParams params;
    params.model = fit.model;
    params.simulation.smooth = fit.smoothing * params.simulation.bins / static_cast<double>(bins);
    return params;
}

std::vector<double> fittedHistogram(const SurfaceFit& fit, const HistogramRow& row) {
    return simulated(fit.model, fit.smoothing, row, fit.nodes);
}

}  // namespace btflut
