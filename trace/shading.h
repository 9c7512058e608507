// Whitted shading from Ray Tracing III: Phong ambient + diffuse + specular per point light with
// hard shadows, plus recursive perfect reflection R_p = … + reflectivity_p · R_q.
#pragma once

#include "trace/precision.h"
#include "trace/world.h"

namespace glint {
inline namespace GLINT_PRECISION {

// Colour seen along `ray` (unclamped), which has already produced `hit` (maybe none).
// `depth` is the number of reflections and transmissions before this hit (0 for the primary
// hit) and `weight` the product of the reflectivities and transmissions along the path so far.
// Counts the rays it casts; for each reflected or transmitted ray that max_depth or
// min_reflectivity keeps from being cast, adds the weight it would have carried to
// `omitted_weight` (its contribution is at most that weight times the radiance it would see).
// `counts` are the pixel's own, and bound its tree: past kMaxTreeRays reflected and transmitted
// rays, further ones are omitted the same way.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayCounts& counts, Real& omitted_weight);

// The most reflected and transmitted rays one pixel's ray tree casts. A hit on glass may cast
// two, so a tree can double at every level: touching glass spheres (SPD's mount) at max_depth 64
// with no weight cut-off would never finish. A chain of reflections (an opaque scene) never
// reaches it; what it cuts is counted in the cut-off bound like any omitted ray.
inline constexpr std::uint64_t kMaxTreeRays = 1024;
// The same at a found hit whose surface point (World::surface) the caller has already rebuilt.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayCounts& counts, Real& omitted_weight);

} // namespace GLINT_PRECISION
} // namespace glint
