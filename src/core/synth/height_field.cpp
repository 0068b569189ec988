#include "core/synth/height_field.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <numbers>

#include "core/random.h"

namespace btflut {

namespace {
// FFTW's planner is not thread-safe; execution is.
std::mutex& plannerMutex() {
    static std::mutex m;
    return m;
}
}  // namespace

Status validateHeightFieldSpec(const HeightFieldSpec& s) {
    if (s.size <= 0) return Error{"size " + std::to_string(s.size) + " must be positive"};
    if (!(s.roughness > 0) || !std::isfinite(s.roughness)) return Error{"roughness must be > 0"};
    if (!(s.roughnessAcross >= 0) || !std::isfinite(s.roughnessAcross))
        return Error{"the anisotropic roughness must be >= 0"};
    if (!(s.correlationLength > 0) || !std::isfinite(s.correlationLength))
        return Error{"correlation length must be > 0"};
    if (s.correlationLength < 4) return Error{"correlation length must be at least 4 pixels to resolve slopes"};
    if (s.correlationLength > s.size / 4.0)
        return Error{"correlation length must be at most size / 4 (" + std::to_string(s.size / 4) + " pixels)"};
    if (!std::isfinite(s.angle)) return Error{"angle must be finite"};
    return success();
}

Result<HeightField> synthesizeHeightField(const HeightFieldSpec& spec) {
    if (Status s = validateHeightFieldSpec(spec); !s) return Error{s.error()};
    const int n = spec.size, half = n / 2 + 1;
    const std::size_t real = static_cast<std::size_t>(n) * n, complex = static_cast<std::size_t>(n) * half;
    using Buffer = std::unique_ptr<double, decltype(&fftw_free)>;
    using Spectrum = std::unique_ptr<fftw_complex, decltype(&fftw_free)>;
    Buffer noise(fftw_alloc_real(real), fftw_free);
    Spectrum white(fftw_alloc_complex(complex), fftw_free), work(fftw_alloc_complex(complex), fftw_free);
    std::vector<Buffer> out;
    for (int i = 0; i < 3; ++i) out.emplace_back(fftw_alloc_real(real), fftw_free);
    if (!noise || !white || !work || !out[0] || !out[1] || !out[2])  // FFTW returns null, it throws nothing
        return Error{"out of memory for a " + std::to_string(n) + " x " + std::to_string(n) + " height field (" +
                     std::to_string((4 * real + 2 * complex) * sizeof(double) >> 20) + " MB of FFT buffers)"};

    // White noise, then its spectrum.
    Random random(spec.seed);
    for (std::size_t i = 0; i < real; i += 2) {
        auto [a, b] = random.normals();
        noise.get()[i] = a;
        if (i + 1 < real) noise.get()[i + 1] = b;
    }
    fftw_plan forward, inverse;
    {
        std::lock_guard lock(plannerMutex());
        forward = fftw_plan_dft_r2c_2d(n, n, noise.get(), white.get(), FFTW_ESTIMATE);
        inverse = fftw_plan_dft_c2r_2d(n, n, work.get(), out[0].get(), FFTW_ESTIMATE);
    }
    fftw_execute(forward);

    // Gaussian spectrum: amplitude exp(-(l_u^2 k_u^2 + l_v^2 k_v^2) / 8) along the rotated axes
    // (the square root of the power spectrum of exp(-d^2 / l^2)). The across-axis correlation
    // length sets the across rms slope: slope ~ height / length.
    const double across = spec.roughnessAcross > 0 ? spec.roughnessAcross : spec.roughness;
    const double lu = spec.correlationLength, lv = spec.correlationLength * spec.roughness / across;
    const double cu = std::cos(spec.angle), su = std::sin(spec.angle);
    auto frequency = [n](int index) { return 2 * std::numbers::pi * (index <= n / 2 ? index : index - n) / n; };
    for (int which = 0; which < 3; ++which) {  // height, d/dx, d/dy
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < half; ++i) {
                const double kx = frequency(i), ky = frequency(j);
                const double ku = cu * kx + su * ky, kv = -su * kx + cu * ky;
                const double amplitude = std::exp(-(lu * lu * ku * ku + lv * lv * kv * kv) / 8);
                const std::size_t at = static_cast<std::size_t>(j) * static_cast<std::size_t>(half) + i;
                std::complex<double> c(white.get()[at][0], white.get()[at][1]);
                c *= amplitude;
                // Spectral derivative; the Nyquist row and column have no well-defined sign.
                const bool nyquist = (n % 2 == 0) && (i == n / 2 || j == n / 2);
                if (which == 1) c *= nyquist ? 0.0 : std::complex<double>(0, kx);
                if (which == 2) c *= nyquist ? 0.0 : std::complex<double>(0, ky);
                work.get()[at][0] = c.real();
                work.get()[at][1] = c.imag();
            }
        fftw_execute_dft_c2r(inverse, work.get(), out[static_cast<std::size_t>(which)].get());
    }
    {
        std::lock_guard lock(plannerMutex());
        fftw_destroy_plan(forward);
        fftw_destroy_plan(inverse);
    }
    HeightField field;
    field.size = n;
    field.height.assign(out[0].get(), out[0].get() + real);
    field.slopeX.assign(out[1].get(), out[1].get() + real);
    field.slopeY.assign(out[2].get(), out[2].get() + real);
    // Scale to the requested rms slope along the principal axis.
    const double scale = spec.roughness / measuredRmsSlope(field, spec.angle);
    for (auto* v : {&field.height, &field.slopeX, &field.slopeY})
        for (double& x : *v) x *= scale;
    return field;
}

double measuredRmsSlope(const HeightField& field, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    double sum = 0;
    for (std::size_t i = 0; i < field.slopeX.size(); ++i) {
        const double slope = c * field.slopeX[i] + s * field.slopeY[i];
        sum += slope * slope;
    }
    return std::sqrt(sum / static_cast<double>(field.slopeX.size()));
}

double HeightField::minHeight() const { return *std::min_element(height.begin(), height.end()); }
double HeightField::maxHeight() const { return *std::max_element(height.begin(), height.end()); }

double HeightField::sample(const std::vector<double>& v, double x, double y) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = x - fx, ty = y - fy;
    const std::size_t x0 = wrap(fx), x1 = wrap(fx + 1), y0 = wrap(fy), y1 = wrap(fy + 1);
    const auto n = static_cast<std::size_t>(size);
    const double a = v[y0 * n + x0], b = v[y0 * n + x1], c = v[y1 * n + x0], d = v[y1 * n + x1];
    return (a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty;
}

}  // namespace btflut
