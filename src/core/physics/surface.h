#pragma once
// The rough-surface model of the paper (section 5): an isotropic Gaussian surface of rms
// slope r whose facets reflect with a local BRDF.
//
//   slopes (p, q) i.i.d. normal with standard deviation r; facet normal m ~ (-p, -q, 1)
//   (eq. 3: P(theta) dw = 1 / (2 pi r^2 cos^3 theta) exp(-tan^2 theta / (2 r^2)) dw)
//   Smith: Lambda(r, theta) (eq. 5); not shadowed given lit P_ill = 1 / (1 + Lambda) (eq. 4),
//   likewise not masked given facing the camera with the view angle.
//
// Values follow the camera: value = min(1, gain * pi * f_r * cos(local incidence)), so a
// white Lambertian facet facing a unit light gives `gain`.

#include <algorithm>
#include <optional>
#include <string>

#include "core/direction/direction.h"
#include "core/result.h"

namespace btflut {

/// Smith's Lambda(r, theta) for rms slope r > 0 and theta in radians; 0 at theta = 0; it
/// diverges towards 90 degrees, where it returns the largest finite double; never NaN or
/// Inf. Evaluated with std::erfc in double (better than 1e-12 relative).
double smithLambda(double r, double theta);

/// Probability that a facet facing the light (or camera) at polar angle theta is not
/// shadowed (masked) by another part of the surface: 1 / (1 + Lambda). 0 at 90 degrees.
double smithUnoccluded(double r, double theta);

/// Slope-space density of eq. 3 per unit macro area and solid angle at facet polar angle
/// theta_m: 1 / (2 pi r^2 cos^3) exp(-tan^2 / (2 r^2)).
double facetDensity(double r, double thetaM);

/// Fresnel reflectance components for light hitting a dielectric of index n >= 1 at
/// incidence angle theta (radians): s- and p-polarised, and their mean (eq. 1, unpolarised).
struct Fresnel {
    double s, p;
    double unpolarised() const { return 0.5 * (s + p); }
};
Fresnel fresnel(double n, double theta);
/// The same from cos(theta), in [0, 1].
Fresnel fresnelFromCos(double n, double cosTheta);

/// Local reflection: kd * Lambert + ks * Torrance-Sparrow (Gaussian facet slopes of width
/// sigma, normalised over projected area, Fresnel with index ior).
struct LocalBrdf {
    double kd = 1;
    double ks = 0;
    double sigma = 0.13;
    double ior = 1.5;
};

struct SurfaceModel {
    double roughness = 0.4;  ///< rms slope r
    LocalBrdf brdf;
    double gain = 1;
};

/// A model from the BRDF's name as flags and files give it: "lambert" uses kd (default 1),
/// "ts" ks (default 1), "mix" needs both. Validated (validateModel); errors name the
/// parameter, prefixed with `what` ("--" for flags, "FILE: " for files).
Result<SurfaceModel> makeSurfaceModel(double roughness, const std::string& brdf, std::optional<double> kd,
                                      std::optional<double> ks, double sigma, double ior, double gain,
                                      const std::string& what);

/// Checks a model's parameters: r > 0, sigma > 0, ior >= 1, kd and ks >= 0, gain > 0, all
/// finite. `what` prefixes the message.
Status validateModel(const SurfaceModel& model, const std::string& what);

/// Camera value of a facet with unit normal m, lit from unit l and seen from unit v (both
/// on the facet's front side) before the camera clips: gain * pi * f_r * (m . l); 0 when
/// the facet faces away from either.
double facetRadiance(const SurfaceModel& model, const Vec3& m, const Vec3& l, const Vec3& v);

/// The camera's value of that facet: facetRadiance clipped at 1 (saturation).
inline double facetValue(const SurfaceModel& model, const Vec3& m, const Vec3& l, const Vec3& v) {
    return std::min(1.0, facetRadiance(model, m, l, v));
}

}  // namespace btflut
