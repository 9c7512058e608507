// Whitted shading from Ray Tracing III: Phong ambient + diffuse + specular per point light with
// hard shadows, plus recursive perfect reflection R_p = … + reflectivity_p · R_q, and (DESIGN
// §11, docs/ARCHITECTURE.md) transmission, shadows through glass and the checker.
#pragma once

#include "trace/render_result.h"
#include "trace/texture.h"
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

// The Phong inputs at a hit (§2's k_a, k_d, k_s, shininess, reflectivity): the material's, with
// its checker cell, base colour texture and vertex colours; for a glTF metallic-roughness
// material, derived per texel as DESIGN §14 says.
struct SurfaceColours {
    Vec3 ambient, diffuse, specular;
    Real shininess, reflectivity;
    bool odd_cell = false;            // the checker's odd cell
    std::optional<TexelSample> texel; // the base colour texture's lookup, where it was read
};
SurfaceColours surface_colours(const World& world, const Hit& hit, const SurfacePoint& surface);

// The reflectivity at a hit, as surface_colours finds it (the material's, or per texel).
Real reflectivity_at(const World& world, const Hit& hit);

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

// A reflected or transmitted ray and the object it may skip (the surface it leaves).
struct SecondaryRay {
    Ray ray;
    std::uint32_t skip;
};
// The perfect reflection of `ray` at `surface`: d' = d − 2n(n·d), n the shading normal.
inline SecondaryRay reflected_ray(const Ray& ray, const SurfacePoint& surface) {
    return {{surface.spawn(), reflect(ray.direction, surface.shading)}, surface.skip};
}
// The ray `ray` transmits at `surface` into or out of a material of index `ior`: refracted,
// or on total internal reflection leaving on the facing side, as a reflection does.
inline SecondaryRay transmitted_ray(const Ray& ray, const SurfacePoint& surface, Real ior) {
    // Entering (the side of the shape's outward normal): from air into the material.
    const Real eta = surface.entering ? 1 / ior : ior;
    bool total = false;
    const Vec3 d = refract(glm::normalize(ray.direction), surface.shading, eta, total);
    if (total) return {{surface.spawn(), d}, surface.skip};
    return {{surface.spawn_through(), d}, surface.skip_through};
}

// Whether a reflected or transmitted ray from a hit at `depth` whose path weight would become
// `next_weight` is cast, with `counts` the rays its tree has cast so far: below max_depth,
// while the weight stays at or above min_reflectivity, and within the tree budget.
inline bool casts_secondary(const RenderSettings& settings, int depth, Real next_weight,
                            const RayCounts& counts) {
    return depth < settings.max_depth && next_weight >= settings.min_reflectivity &&
           counts.reflection + counts.transmission < kMaxTreeRays;
}

// What a caller cast ahead for the hits of pixels' ray trees, level by level in packets with
// the neighbours' rays (TileLighting, trace/pixel.h): one node per hit found before shade()
// reaches it, numbered from the pixels' primary hits on.
struct AheadNode {
    static constexpr std::uint32_t kNone = ~0u;
    Ray ray; // the ray that found the hit: the camera's, or the one shade() casts there
    Hit hit;
    Real weight; // the path weight there
    // The nodes of the hits of the reflected_ray and transmitted_ray from here (which shade()
    // casts exactly where casts_secondary says so), or kNone where shade() casts them itself.
    std::uint32_t next[2] = {kNone, kNone};
};
struct CastAhead {
    const SurfacePoint* surfaces = nullptr; // node n's, where its hit is found; null: none made
    const AheadNode* nodes = nullptr;       // null: no reflected or transmitted ray cast ahead
    // Node n's shadow verdicts at light[n · lights + j], where not null and n < lit: per light, the
    // factor light_through would find, or kThroughGlass where the first shadow ray meets glass and
    // nothing opaque (shade() then follows the glass crossings itself); for every light in
    // front of the surface.
    const Real* light = nullptr;
    std::uint32_t node = AheadNode::kNone; // the hit being shaded
    std::uint32_t lit = 0;
};

// Colour seen along `ray` (unclamped), which has already produced `hit` (maybe none).
// `depth` is the number of reflections and transmissions before this hit (0 for the primary
// hit) and `weight` the product of the reflectivities and transmissions along the path so far.
// Adds to `tree`, the pixel's, what it casts and what it omits; for each omitted ray, the weight
// it would have carried (its contribution is at most that weight times the radiance it sees).
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayTree& tree);
// The same at a found hit whose surface point (World::surface) the caller has already rebuilt,
// and with what it has cast ahead: shade counts those rays as its own without casting them.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayTree& tree, const CastAhead& ahead = {});

} // namespace GLINT_PRECISION
} // namespace glint
