#pragma once
// The viewer's two cameras: an orbit around a target (3D), and a frontal orthographic view of
// one quad (2D), in which zoom 1 shows one texel of the reference per window pixel.

#include <algorithm>
#include <cmath>

#include "core/data/scene.h"

namespace btflut {

/// Camera on a sphere around its target.
struct Orbit {
    Vec3 target;
    double azimuth = -M_PI / 2, elevation = 1.15, distance = 3.6;

    Vec3 eye() const {
        return {target.x + distance * std::cos(elevation) * std::cos(azimuth),
                target.y + distance * std::cos(elevation) * std::sin(azimuth),
                target.z + distance * std::sin(elevation)};
    }
    static Orbit of(const Scene& s) {
        Orbit o;
        o.target = s.target;
        const Vec3 d{s.eye.x - s.target.x, s.eye.y - s.target.y, s.eye.z - s.target.z};
        o.distance = std::hypot(d.x, d.y, d.z);
        o.elevation = std::asin(std::clamp(d.z / o.distance, -1.0, 1.0));
        o.azimuth = std::atan2(d.y, d.x);
        return o;
    }
};

/// Frontal orthographic view of a quad lying in the z = 0 plane (normal +z, tangent +x), in
/// texel units of an image `texelsWide` x `texelsHigh` that spans it.
struct FlatView {
    double zoom = 1;            ///< window pixels per texel
    double panX = 0, panY = 0;  ///< the texel at the pane's centre, from the image's centre (y up)

    /// The zoom that fits the image in a pane, and no pan.
    void fit(int paneWidth, int paneHeight, int texelsWide, int texelsHigh) {
        zoom = std::min(static_cast<double>(paneWidth) / texelsWide, static_cast<double>(paneHeight) / texelsHigh);
        panX = panY = 0;
    }
    /// Zooms by `factor` keeping the texel under pane pixel (x, y) (origin bottom left) in place.
    void zoomAbout(double factor, double x, double y, int paneWidth, int paneHeight) {
        const double cx = x - paneWidth / 2.0, cy = y - paneHeight / 2.0;
        const double tx = panX + cx / zoom, ty = panY + cy / zoom;
        zoom = std::clamp(zoom * factor, 1.0 / 64, 64.0);
        panX = tx - cx / zoom, panY = ty - cy / zoom;
    }
    /// The camera for a pane: the image's texel edges fall on pixel edges (so at zoom 1 each
    /// pixel is one texel, unfiltered), whatever the parity of the pane's and image's sizes.
    void apply(Scene& scene, const SceneQuad& quad, int paneWidth, int paneHeight, int texelsWide,
               int texelsHigh) const {
        const double worldPerTexel = quad.height / texelsHigh;
        auto snapped = [&](double pan, int pane, int texels) {
            // The image's left (bottom) edge in pane pixels, moved to the nearest whole pixel.
            const double edge = std::round(pane / 2.0 - (texels / 2.0 + pan) * zoom);
            return (pane / 2.0 - edge) / zoom - texels / 2.0;
        };
        const double x = snapped(panX, paneWidth, texelsWide) * worldPerTexel;
        const double y = snapped(panY, paneHeight, texelsHigh) * worldPerTexel;
        scene.target = {quad.center.x + x, quad.center.y + y, quad.center.z};
        scene.eye = {scene.target.x, scene.target.y, scene.target.z + 4 * std::max(quad.width, quad.height)};
        scene.up = {0, 1, 0};
        scene.orthographicHeight = paneHeight / zoom * worldPerTexel;
    }
};

}  // namespace btflut
