#include "core/synth/render.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/random.h"

namespace btflut {

namespace {

constexpr double kStep = 0.5;  // pixels: marching step, well below the correlation length

struct Hit {
    double x, y, z;
};

// The first surface point along the ray that crosses the mean plane at (x, y), coming from
// the camera at direction v: the largest t with z(t) <= h(x(t), y(t)), z(t) = t v_z.
Hit firstHit(const HeightField& f, const Vec3& v, double x, double y, double top, double bottom) {
    if (v.z > 1 - 1e-12) return {x, y, f.heightAt(x, y)};
    const double horizontal = std::hypot(v.x, v.y);
    const double dt = kStep / std::max(horizontal, v.z);
    auto above = [&](double t) { return t * v.z - f.heightAt(x + t * v.x, y + t * v.y); };
    double t = (top + 1e-9) / v.z;
    const double tEnd = (bottom - 1) / v.z;
    while (t > tEnd && above(t - dt) > 0) t -= dt;
    // The crossing lies in [t - dt, t]: bisect.
    double lo = t - dt, hi = t;
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (above(mid) > 0 ? hi : lo) = mid;
    }
    return {x + lo * v.x, y + lo * v.y, lo * v.z};
}

bool castShadow(const HeightField& f, const Vec3& l, const Hit& h, double top) {
    if (l.z > 1 - 1e-12) return false;
    const double horizontal = std::hypot(l.x, l.y);
    const double ds = kStep / std::max(horizontal, l.z);
    for (double s = ds; h.z + s * l.z <= top; s += ds)
        if (h.z + s * l.z < f.heightAt(h.x + s * l.x, h.y + s * l.y) - 1e-9) return true;
    return false;
}

}  // namespace

Image renderHeightField(const HeightField& field, const SurfaceModel& model, Direction light, Direction view,
                        const RenderOptions& o) {
    const int n = field.size, s = std::max(1, o.samplesPerAxis);
    const Vec3 l = toVector(light), v = toVector(view);
    const double top = field.maxHeight(), bottom = field.minHeight();
    Image image(n, n, 1, 16);
    auto albedoAt = [&](double x, double y) {
        if (!o.albedo) return 1.0;
        return (*o.albedo)[field.wrap(y) * static_cast<std::size_t>(n) + field.wrap(x)];
    };
    parallelFor(static_cast<std::size_t>(n), o.threads, [&](std::size_t rowIndex) {
        const int row = static_cast<int>(rowIndex);
        Random noise(o.noiseSeed * 0x9e3779b97f4a7c15ull + rowIndex);  // per row: thread-independent
        for (int i = 0; i < n; ++i) {
            double sum = 0;
            for (int sy = 0; sy < s; ++sy)
                for (int sx = 0; sx < s; ++sx) {
                    const double x = i + (sx + 0.5) / s, y = (n - row - 1) + (sy + 0.5) / s;
                    const Hit hit = firstHit(field, v, x, y, top, bottom);
                    const double p = field.slopeXAt(hit.x, hit.y), q = field.slopeYAt(hit.x, hit.y);
                    const double len = std::sqrt(1 + p * p + q * q);
                    const Vec3 m{-p / len, -q / len, 1 / len};
                    const double albedo = albedoAt(hit.x, hit.y);
                    sum += o.ambient * albedo * model.brdf.kd * model.gain;
                    if (m.x * l.x + m.y * l.y + m.z * l.z <= 0 || castShadow(field, l, hit, top)) continue;
                    sum += albedo * facetRadiance(model, m, l, v);
                }
            double value = sum / (s * s);
            if (o.noise > 0) value += o.noise * noise.normals().first;
            image.at(i, row, 0) = static_cast<float>(std::clamp(value, 0.0, 1.0));
        }
    });
    return image;
}

}  // namespace btflut
