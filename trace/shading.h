// Whitted shading from Ray Tracing III: Phong ambient + diffuse + specular per point light with
// hard shadows, plus recursive perfect reflection R_p = … + reflectivity_p · R_q, and (DESIGN
// §11, docs/ARCHITECTURE.md) transmission, shadows through glass and the checker.
#pragma once

#include "trace/precision.h"
#include "trace/world.h"

namespace glint {
inline namespace GLINT_PRECISION {

// The most reflected and transmitted rays one pixel's ray tree casts. A hit on glass may cast
// two, so a tree can double at every level: touching glass spheres (SPD's mount) at max_depth 64
// with no weight cut-off would never finish. A chain of reflections (an opaque scene) never
// reaches it; what it cuts is counted in the cut-off bound like any omitted ray.
inline constexpr std::uint64_t kMaxTreeRays = 1024;

// What one pixel's ray tree tallies besides its colour.
struct RayTree {
    RayCounts rays; // every ray it cast: the primary ray, shadow, reflected, transmitted
    // The summed path weights of the reflected and transmitted rays that max_depth,
    // min_reflectivity or kMaxTreeRays kept from being cast (trace/cutoff.h).
    Real omitted_weight = 0;
    int depth = 0; // the deepest level it cast a ray at (0: the primary ray alone)
    // What the tree met, in the order it met it: each hit's object (or the background) and
    // checker cell parity, and each light's shadow verdict (lit, blocked, or the number of glass
    // segments it passed). Two pixels whose keys differ see different things along their paths:
    // the adaptive antialiasing rule (trace/sampling.h) refines them.
    std::uint64_t path_key = 0;

    void note(std::uint64_t event) {
        path_key = (path_key + event + 0x9e3779b97f4a7c15u) * 0xff51afd7ed558ccdu;
        path_key ^= path_key >> 32;
    }
};

// Colour seen along `ray` (unclamped), which has already produced `hit` (maybe none).
// `depth` is the number of reflections and transmissions before this hit (0 for the primary
// hit) and `weight` the product of the reflectivities and transmissions along the path so far.
// Adds to `tree`, the pixel's, what it casts and what it omits; for each omitted ray, the weight
// it would have carried (its contribution is at most that weight times the radiance it sees).
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayTree& tree);
// The same at a found hit whose surface point (World::surface) the caller has already rebuilt.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayTree& tree);

} // namespace GLINT_PRECISION
} // namespace glint
