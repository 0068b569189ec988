#include "core/physics/surface.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace btflut {

namespace {
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
}  // namespace

double smithLambda(double r, double theta) {
    theta = std::abs(theta);
    if (theta == 0) return 0;
    // Lambda diverges at the horizon; the largest finite double keeps sums and products free
    // of Inf and NaN, and smithUnoccluded returns exactly 0 there.
    if (theta >= std::numbers::pi / 2) return std::numeric_limits<double>::max();
    // With a = cot(theta) / (sqrt(2) r): Lambda = (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2.
    // The two terms agree to about 1 / (2 a^2) before exp(-a^2) underflows (a < 27), so the
    // difference keeps better than 1e-12 relative precision.
    const double a = 1.0 / (std::tan(theta) * std::numbers::sqrt2 * r);
    if (a > 27) return 0;  // exp(-a^2) underflows; Lambda < 1e-320
    return 0.5 * (std::exp(-a * a) / (a * std::sqrt(std::numbers::pi)) - std::erfc(a));
}

double smithUnoccluded(double r, double theta) {
    if (std::abs(theta) >= std::numbers::pi / 2) return 0.0;
    return 1.0 / (1.0 + smithLambda(r, theta));
}

double facetDensity(double r, double thetaM) {
    const double c = std::cos(thetaM), t = std::tan(thetaM);
    return std::exp(-t * t / (2 * r * r)) / (2 * std::numbers::pi * r * r * c * c * c);
}

Fresnel fresnel(double n, double theta) { return fresnelFromCos(n, std::cos(theta)); }

Fresnel fresnelFromCos(double n, double ci) {
    ci = std::clamp(ci, 0.0, 1.0);
    // cos of the refracted angle from Snell's law: sin t = sin i / n.
    const double st2 = (1 - ci * ci) / (n * n);
    const double ct = std::sqrt(std::max(0.0, 1 - st2));
    const double rs = (ci - n * ct) / (ci + n * ct);
    const double rp = (n * ci - ct) / (n * ci + ct);
    return {rs * rs, rp * rp};
}

Result<SurfaceModel> makeSurfaceModel(double roughness, const std::string& brdf, std::optional<double> kd,
                                      std::optional<double> ks, double sigma, double ior, double gain,
                                      const std::string& what) {
    SurfaceModel model;
    model.roughness = roughness;
    model.gain = gain;
    model.brdf.sigma = sigma;
    model.brdf.ior = ior;
    if (brdf == "lambert") {
        model.brdf.kd = kd.value_or(1.0);
        model.brdf.ks = 0;
    } else if (brdf == "ts") {
        model.brdf.kd = 0;
        model.brdf.ks = ks.value_or(1.0);
    } else if (brdf == "mix") {
        if (!kd || !ks) return Error{what + "brdf mix needs kd and ks"};
        model.brdf.kd = *kd;
        model.brdf.ks = *ks;
    } else {
        return Error{what + "brdf '" + brdf + "' is not lambert, ts or mix"};
    }
    if (Status s = validateModel(model, what); !s) return Error{s.error()};
    return model;
}

Status validateModel(const SurfaceModel& m, const std::string& what) {
    auto bad = [&](const std::string& name, double v, const std::string& rule) {
        char number[32];
        std::snprintf(number, sizeof number, "%g", v);
        return Error{what + name + " " + number + " " + rule};
    };
    if (!std::isfinite(m.roughness) || m.roughness <= 0) return bad("roughness", m.roughness, "must be > 0");
    if (!std::isfinite(m.brdf.sigma) || m.brdf.sigma <= 0) return bad("sigma", m.brdf.sigma, "must be > 0");
    if (!std::isfinite(m.brdf.ior) || m.brdf.ior < 1) return bad("ior", m.brdf.ior, "must be >= 1");
    if (!std::isfinite(m.brdf.kd) || m.brdf.kd < 0) return bad("kd", m.brdf.kd, "must be >= 0");
    if (!std::isfinite(m.brdf.ks) || m.brdf.ks < 0) return bad("ks", m.brdf.ks, "must be >= 0");
    if (!std::isfinite(m.gain) || m.gain <= 0) return bad("gain", m.gain, "must be > 0");
    return success();
}

double facetRadiance(const SurfaceModel& model, const Vec3& m, const Vec3& l, const Vec3& v) {
    const double cosI = dot(m, l), cosR = dot(m, v);
    if (cosI <= 0 || cosR <= 0) return 0;
    double value = model.brdf.kd * cosI;  // pi * (kd / pi) * cos i
    if (model.brdf.ks > 0) {
        Vec3 h{l.x + v.x, l.y + v.y, l.z + v.z};
        const double len = std::sqrt(dot(h, h));
        if (len > 0) {
            h = {h.x / len, h.y / len, h.z / len};
            const double cosAlpha = dot(m, h);
            if (cosAlpha > 0) {
                // Facet-slope Gaussian of width sigma, normalised so that its projected area
                // integrates to 1 (the same form as eq. 3).
                const double s2 = model.brdf.sigma * model.brdf.sigma;
                const double tan2 = (1 - cosAlpha * cosAlpha) / (cosAlpha * cosAlpha);
                const double d =
                    std::exp(-tan2 / (2 * s2)) / (2 * std::numbers::pi * s2 * cosAlpha * cosAlpha * cosAlpha);
                const double f = fresnelFromCos(model.brdf.ior, dot(l, h)).unpolarised();
                // pi * f_r * cos i with f_r = F D / (4 cos i cos r)
                value += model.brdf.ks * std::numbers::pi * f * d / (4 * cosR);
            }
        }
    }
    value *= model.gain;
    return std::isfinite(value) ? value : std::numeric_limits<double>::max();
}

}  // namespace btflut
