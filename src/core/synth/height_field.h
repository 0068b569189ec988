#pragma once
// Periodic Gaussian random height fields by spectral synthesis, the ground truth of the
// rough-surface model: a field of rms slope r has slopes (p, q) that are normal with
// standard deviation r, as eq. 3 assumes.
//
//   Result<HeightField> f = synthesizeHeightField({.size = 512, .roughness = 0.4});
//   double h = f->heightAt(10.5, 3.25);          // bilinear, periodic, pixel units
//
// Heights and horizontal coordinates are in pixels. The spectrum is Gaussian (correlation
// function exp(-d^2 / l^2)), band-limited well below the pixel grid for l >= 4, and slopes
// are exact spectral derivatives. Anisotropy: a second rms slope along the axis rotated by
// `angle` + 90 degrees (via a shorter or longer correlation length there).

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/result.h"

namespace btflut {

struct HeightFieldSpec {
    int size = 512;                 ///< N x N samples, periodic; a power of two or any FFTW size
    double roughness = 0.4;         ///< rms slope along the principal axis
    double roughnessAcross = 0;     ///< rms slope across it; 0: isotropic (= roughness)
    double angle = 0;               ///< principal axis, radians from x towards y
    double correlationLength = 16;  ///< pixels, along the principal axis
    std::uint64_t seed = 1;
};

/// Refuses non-positive size, roughness or correlation length, a correlation length below 4
/// pixels (slopes would not be resolved) or above size / 4 (too few independent features).
Status validateHeightFieldSpec(const HeightFieldSpec& spec);

struct HeightField {
    int size = 0;
    std::vector<double> height, slopeX, slopeY;  ///< size x size, row y, column x

    double heightAt(double x, double y) const { return sample(height, x, y); }
    double slopeXAt(double x, double y) const { return sample(slopeX, x, y); }
    double slopeYAt(double x, double y) const { return sample(slopeY, x, y); }
    /// The grid column (or row) holding coordinate c, wrapped periodically into [0, size).
    std::size_t wrap(double c) const {
        auto k = static_cast<long>(std::floor(c)) % size;
        return static_cast<std::size_t>(k < 0 ? k + size : k);
    }
    double minHeight() const;
    double maxHeight() const;

private:
    double sample(const std::vector<double>& v, double x, double y) const;
};

Result<HeightField> synthesizeHeightField(const HeightFieldSpec& spec);

/// Measured rms slope along the axis at `angle` (radians from x towards y).
double measuredRmsSlope(const HeightField& field, double angle);

}  // namespace btflut
