// Whitted shading from Ray Tracing III: Phong ambient + diffuse + specular per point light with
// hard shadows, plus recursive perfect reflection R_p = … + reflectivity_p · R_q, and (DESIGN
// §11, docs/ARCHITECTURE.md) transmission, shadows through glass and the checker.
#pragma once

#include "trace/render_result.h"
#include "trace/world.h"

namespace glint {
inline namespace GLINT_PRECISION {

// The most reflected and transmitted rays one pixel's ray tree casts. A hit on glass may cast
// two, so a tree can double at every level: touching glass spheres (SPD's mount) at max_depth 64
// with no weight cut-off would never finish. A chain of reflections (an opaque scene) never
// reaches it; what it cuts is counted in the cut-off bound like any omitted ray.
inline constexpr std::uint64_t kMaxTreeRays = 1024;

// Shadow rays are followed through at most this many transmissive crossings; a light behind more
// is taken as blocked (64 panes of glass pass at most 0.9⁶⁴ ≈ 1e-3 of it).
inline constexpr int kMaxCrossings = 64;

class RayRecorder; // trace/recorder.h

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
    // Where shading reports the tree as it walks it (`glint explain`); null while rendering.
    RayRecorder* recorder = nullptr;

    void note(std::uint64_t event) {
        path_key = (path_key + event + 0x9e3779b97f4a7c15u) * 0xff51afd7ed558ccdu;
        path_key ^= path_key >> 32;
    }
};

// Whether `light` is in front of the surface (n·l > 0, n the shading normal), with l and n·l:
// shade() casts a shadow ray only then, and a tile's shadow packets (trace/pixel.h) ask the same.
struct LightDirection {
    Vec3 l;
    Real n_dot_l;
    bool in_front() const { return n_dot_l > 0; }
};
inline LightDirection light_direction(const SurfacePoint& surface, const Light& light) {
    const Vec3 l = glm::normalize(light.position - surface.position);
    return {l, glm::dot(surface.shading, l)};
}

// The shadow ray towards a light at `position` from a surface: spawned off the surface, ending at
// the light at t = 1, skipping what the surface may skip.
inline Ray shadow_ray(const SurfacePoint& surface, Vec3 position) {
    const Vec3 from = surface.spawn();
    return {from, position - from};
}

// A shadow verdict cast ahead (TileLighting, trace/pixel.h) where glass and nothing opaque lies
// on the shadow ray: shade() follows it crossing by crossing.
inline constexpr Real kThroughGlass = -1;

// Colour seen along `ray` (unclamped), which has already produced `hit` (maybe none).
// `depth` is the number of reflections and transmissions before this hit (0 for the primary
// hit) and `weight` the product of the reflectivities and transmissions along the path so far.
// Adds to `tree`, the pixel's, what it casts and what it omits; for each omitted ray, the weight
// it would have carried (its contribution is at most that weight times the radiance it sees).
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayTree& tree);
// The same at a found hit whose surface point (World::surface) the caller has already rebuilt.
// `known_light`, when given, holds per light the factor light_through would find, or
// kThroughGlass where its first shadow ray meets glass and nothing opaque (cast by the caller in
// packets, for the lights in front of the surface); shade then counts those shadow rays without
// casting them, and follows the glass crossings itself.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayTree& tree, const Real* known_light = nullptr);

} // namespace GLINT_PRECISION
} // namespace glint
