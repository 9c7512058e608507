// One pixel's path, the only one: its primary hit (by camera ray or from the item buffer's ids,
// trace/primary_hits.h), then Whitted shading (trace/shading.h). The headless render, the hybrid
// resolve and the preview's refiner all trace pixels through here; what a view or a report
// shows beside the colour comes from what this path computed, not from a second intersection.
#pragma once

#include "trace/primary_hits.h"
#include "trace/shading.h"

namespace glint {
inline namespace GLINT_PRECISION {

// A pixel's colour and what its path found: the ray tree's tallies (trace/shading.h) and the
// primary hit, from which the preview's views are drawn.
struct PixelSample : RayTree {
    Vec3 colour{0}; // unclamped
    Hit hit;        // the primary hit (maybe none)
    Vec3 normal{0}; // unit shading normal at the primary hit; zero where there is none
};

// Shades a camera ray from its primary hit.
PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary);

// The whole path of pixel (x, y): its camera ray, made once, its primary hit from `source`,
// then shading.
inline PixelSample trace_pixel(const World& world, const PrimarySource& source, int x, int y,
                               PrimaryStats& stats) {
    const Ray ray = world.camera().ray(x, y);
    return shade_pixel(world, ray, primary_hit(world, source, x, y, ray, stats));
}

} // namespace GLINT_PRECISION
} // namespace glint
