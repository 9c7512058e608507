#include "trace/shading.h"

#include "trace/recorder.h"
#include "trace/texture.h"

#include <algorithm>
#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {

Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayTree& tree) {
    if (!hit.found()) {
        tree.note(0);
        return world.missed(ray);
    }
    return shade(world, ray, hit, world.surface(ray, hit), depth, weight, tree);
}

namespace {

// Whether the checker's cell at object-space point q is odd (docs/SCENES.md): k = ⌊q.x/s⌋ +
// ⌊q.z/s⌋ on shapes whose checker lies in their plane (planes, disks), + ⌊q.y/s⌋ on the others;
// the parity in the floor sense (k = −1 is odd). In double: the floors are exact integers.
bool odd_cell(Real size, Vec3 q, bool in_plane) {
    const double s = size;
    double k = std::floor(q.x / s) + std::floor(q.z / s);
    if (!in_plane) k += std::floor(q.y / s);
    return std::fmod(k, 2.0) != 0;
}

// A texture's lookup at a hit, where there is a texture and the object is a mesh with the
// texture coordinate set it reads (docs/SCENES.md, "Textures"): at the hit's barycentrics, the
// same in every pixel path, so hybrid and ray mode see the same texels.
std::optional<TexelSample> texture_at(const World& world, const Texture* texture, const Hit& hit) {
    if (!texture) return std::nullopt;
    const Mesh* mesh = world.objects()[hit.object].params.mesh;
    if (!mesh || mesh_uvs(*mesh, texture->set).empty()) return std::nullopt;
    return sample_texture(*texture, mesh_uv(*mesh, hit.primitive, hit.u, hit.v, texture->set));
}

// A mesh's vertex colour at a hit (glTF's COLOR_0), or none.
std::optional<Vec3> vertex_colour(const World& world, const Hit& hit) {
    const Mesh* mesh = world.objects()[hit.object].params.mesh;
    if (!mesh || mesh->colours.empty()) return std::nullopt;
    const glm::uvec3 tri = mesh->triangles[hit.primitive];
    const Real b1 = hit.u, b2 = hit.v, b0 = 1 - b1 - b2;
    return b0 * Vec3(mesh->colours[tri.x]) + b1 * Vec3(mesh->colours[tri.y]) +
           b2 * Vec3(mesh->colours[tri.z]);
}

// The material's emission at a hit (DESIGN §13): its colour × the emission texture's there. An
// emission texture the mesh cannot read (no coordinates of its set) leaves no emission (§14).
// An unlit material's colour comes this way too: its base colour, which such a texture leaves as
// the factor, × the vertex colours.
Vec3 emission_at(const World& world, const Phong& m, const Hit& hit) {
    if (m.emission == Vec3(0.0_r)) return Vec3(0.0_r);
    Vec3 e = m.emission;
    if (m.emission_texture) {
        const std::optional<TexelSample> texel = texture_at(world, m.emission_texture, hit);
        if (texel) e *= Vec3(texel->colour);
        else if (!m.unlit) return Vec3(0.0_r);
    }
    if (m.unlit)
        if (const std::optional<Vec3> c = vertex_colour(world, hit)) e *= *c;
    return e;
}

// A glTF material's metallic m and roughness r at a hit (DESIGN §14): the factors × the
// metallic-roughness texel's blue and green.
std::pair<Real, Real> metal_rough_at(const World& world, const Phong::MetalRough& p,
                                     const Hit& hit) {
    const std::optional<TexelSample> texel = texture_at(world, p.metal_rough, hit);
    return texel
               ? std::pair{p.metallic * Real(texel->colour.z), p.roughness * Real(texel->colour.y)}
               : std::pair{p.metallic, p.roughness};
}

Real reflectivity_of(Real metallic, Real roughness, Real coverage) {
    return metallic * (1 - roughness) * (1 - roughness) * coverage;
}

// The fraction of a light's colour that passes the glass on the shadow ray from `surface` to
// `light`, on which nothing opaque lies: the product of the transmissions of the surfaces it
// crosses, each piece between crossings one more shadow ray (the first one counted already).
Real through_glass(const World& world, const SurfacePoint& surface, Vec3 light, RayCounts& counts) {
    Vec3 from = surface.spawn();
    std::uint32_t skip = surface.skip;
    Real through = 1;
    for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        const Ray segment{from, light - from};
        const Hit hit = world.intersect(segment, 1.0_r, skip);
        if (!hit.found()) return through;
        through *= world.material(hit.object).transmission;
        if (through == 0) return 0;
        const SurfacePoint crossed = world.surface(segment, hit);
        from = crossed.spawn_through();
        skip = crossed.skip_through;
        ++counts.shadow;
    }
    return 0;
}

// The fraction of a light's colour that reaches a surface from `light` (docs/ARCHITECTURE.md,
// "Conventions": shadows): 1 when nothing lies on the open segment, else the product of the
// transmissions of every surface the segment crosses (0 at the first opaque one). Shadow rays
// are not bent; each piece of the segment between crossings is one shadow ray. Without a
// transmissive material in the scene, one any-hit query answers it; with one, an any-hit query
// for opaque objects first, so that only segments that meet glass and nothing opaque are
// followed crossing by crossing. `known`: that first query's answer, cast already in a packet
// (TileLighting), or null.
Real light_through(const World& world, const SurfacePoint& surface, Vec3 light, RayCounts& counts,
                   const Real* known) {
    ++counts.shadow;
    if (known)
        return *known == kThroughGlass ? through_glass(world, surface, light, counts) : *known;
    const Ray shadow = shadow_ray(surface, light);
    if (!world.geometry()->transmissive)
        return world.occluded(shadow, 1.0_r, surface.skip) ? 0.0_r : 1.0_r;
    bool glass = false;
    if (world.opaque_between(shadow, 1.0_r, surface.skip, glass)) return 0;
    return glass ? through_glass(world, surface, light, counts) : 1;
}

} // namespace

namespace {

// surface_colours, inlined into shade(): most hits take its first return.
[[gnu::always_inline]] inline SurfaceColours colours_at(const World& world, const Hit& hit,
                                                        const SurfacePoint& surface) {
    const Phong& m = world.material(hit.object);
    SurfaceColours out{m.ambient, m.diffuse, m.specular, m.shininess, m.reflectivity, false, {}};
    out.odd_cell = m.checker_size > 0 &&
                   odd_cell(m.checker_size, surface.object_point,
                            shape_traits(world.objects()[hit.object].shape).checker_in_plane);
    if (out.odd_cell) out.diffuse = m.checker_diffuse, out.ambient = m.checker_ambient;
    // The base colour: the material's (or its checker cell's) × texel × vertex colour; most
    // surfaces have neither, and skip the products.
    Vec3 base(1.0_r);
    bool tinted = false;
    out.texel = texture_at(world, m.texture, hit);
    if (out.texel) base = Vec3(out.texel->colour), tinted = true;
    // A mesh's vertex colours multiply the base colour too (glTF's COLOR_0).
    if (const std::optional<Vec3> c = vertex_colour(world, hit)) base *= *c, tinted = true;
    if (!m.metal_rough) {
        if (tinted) out.diffuse *= base, out.ambient *= base;
        return out;
    }
    // DESIGN §14, per texel; BLEND's coverage scales what shows of the surface.
    const Phong::MetalRough& p = *m.metal_rough;
    const Vec3 b = p.base * base;
    const auto [metallic, roughness] = metal_rough_at(world, p, hit);
    Real occlusion = 1;
    if (const std::optional<TexelSample> o = texture_at(world, p.occlusion, hit))
        occlusion = 1 + p.occlusion_strength * (Real(o->colour.x) - 1);
    out.diffuse = b * ((1 - metallic) * (1 - p.transmission) * p.coverage);
    out.specular = (Vec3(0.04_r * (1 - metallic)) + b * metallic) * p.coverage;
    const Real alpha = roughness * roughness;
    out.shininess = alpha > 0 ? std::clamp(2 / (alpha * alpha) - 2, 1.0_r, 1e6_r) : 1e6_r;
    out.reflectivity = reflectivity_of(metallic, roughness, p.coverage);
    out.ambient = occlusion * (out.diffuse + out.specular * (1 - out.reflectivity));
    return out;
}

} // namespace

SurfaceColours surface_colours(const World& world, const Hit& hit, const SurfacePoint& surface) {
    return colours_at(world, hit, surface);
}

Real reflectivity_at(const World& world, const Hit& hit) {
    const Phong& m = world.material(hit.object);
    if (!m.metal_rough) return m.reflectivity;
    const auto [metallic, roughness] = metal_rough_at(world, *m.metal_rough, hit);
    return reflectivity_of(metallic, roughness, m.metal_rough->coverage);
}

// The lecture's sum, with §11's checker, shadows through glass and transmitted rays, in one
// body: the local terms and the two kinds of secondary ray share the weight rule and its
// counters.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayTree& tree, const CastAhead& ahead) {
    RayCounts& counts = tree.rays;
    const Phong& m = world.material(hit.object);
    const Vec3 n = surface.shading;
    const Vec3 v = -glm::normalize(ray.direction);
    const SurfaceColours colours = colours_at(world, hit, surface);
    const Vec3 &diffuse = colours.diffuse, &ambient = colours.ambient, &specular = colours.specular;
    const bool odd = colours.odd_cell;
    const std::optional<TexelSample>& texel = colours.texel;
    tree.note((static_cast<std::uint64_t>(hit.object) + 1) * 2 + (odd ? 1 : 0));
    RayRecorder* const recorder = tree.recorder;
    const Real* const known_light =
        ahead.light && ahead.node < ahead.lit
            ? ahead.light + static_cast<std::size_t>(ahead.node) * world.lights().size()
            : nullptr;

    // Emission is added once here, unshadowed; the parent weights it with the rest.
    const Vec3 emission = emission_at(world, m, hit);
    Vec3 colour = ambient * world.ambient() + emission;
    if (recorder) recorder->surface(surface, odd, texel, ambient * world.ambient(), emission);
    // An unlit surface's colour is its emission: no light adds to it.
    const std::size_t lights = m.unlit ? 0 : world.lights().size();
    for (std::size_t j = 0; j < lights; ++j) {
        const Light& light = world.lights()[j];
        const auto [l, n_dot_l] = light_direction(surface, light);
        const auto index = static_cast<std::uint32_t>(j);
        if (n_dot_l <= 0) { // the light is behind the surface
            if (recorder) recorder->light({index, n_dot_l});
            continue;
        }
        const std::uint64_t shadow_rays = counts.shadow;
        const Real through = light_through(world, surface, light.position, counts,
                                           known_light ? &known_light[j] : nullptr);
        // The verdict: blocked, or how many segments (1 + glass crossings) reached the light.
        tree.note(through == 0 ? ~std::uint64_t{0} : counts.shadow - shadow_rays);
        if (through == 0) {
            if (recorder) recorder->light({index, n_dot_l, 0, counts.shadow - shadow_rays});
            continue;
        }
        Vec3 lit = diffuse * n_dot_l;
        Real highlight = 0; // (r·v)^shininess
        if (specular != Vec3(0.0_r)) { // pow is dear, and NFF's matte surfaces have 1e5
            const Vec3 r = 2.0_r * n * n_dot_l - l; // reflect(−l, n)
            highlight = std::pow(glm::max(0.0_r, glm::dot(r, v)), colours.shininess);
            lit += specular * highlight;
        }
        colour += (through * light.color) * lit;
        if (recorder)
            recorder->light({index, n_dot_l, through, counts.shadow - shadow_rays,
                             (through * light.color) * (diffuse * n_dot_l),
                             (through * light.color) * (specular * highlight)});
    }

    // Reflected and transmitted rays, each cast only while it can still matter
    // (casts_secondary); otherwise its weight is what the cut-off may have cost.
    const RenderSettings& settings = world.settings();
    // `make_next` makes the ray; a ray cast ahead comes with its node.
    const auto follow = [&](RayKind kind, Real factor, const auto& make_next) {
        const Real next_weight = weight * factor;
        if (!casts_secondary(settings, depth, next_weight, counts)) {
            tree.omitted_weight += next_weight;
            if (recorder)
                recorder->omitted(kind, next_weight,
                                  depth >= settings.max_depth ? OmittedRay::Why::max_depth
                                  : next_weight < settings.min_reflectivity
                                      ? OmittedRay::Why::min_weight
                                      : OmittedRay::Why::tree_budget);
            return;
        }
        ++(kind == RayKind::reflection ? counts.reflection : counts.transmission);
        tree.depth = std::max(tree.depth, depth + 1);
        const std::uint32_t known =
            ahead.nodes ? ahead.nodes[ahead.node].next[kind == RayKind::transmission]
                        : AheadNode::kNone;
        Vec3 seen;
        if (known == AheadNode::kNone) {
            const SecondaryRay next = make_next();
            const Hit next_hit = world.intersect(next.ray, kInfinity, next.skip);
            if (recorder) recorder->begin(kind, next.ray, next_hit, factor, next_weight, depth + 1);
            seen = shade(world, next.ray, next_hit, depth + 1, next_weight, tree);
        } else {
            const AheadNode& node = ahead.nodes[known];
            if (recorder) recorder->begin(kind, node.ray, node.hit, factor, next_weight, depth + 1);
            seen = node.hit.found()
                       ? shade(world, node.ray, node.hit, ahead.surfaces[known], depth + 1,
                               next_weight, tree,
                               {ahead.surfaces, ahead.nodes, ahead.light, known, ahead.lit})
                       : shade(world, node.ray, node.hit, depth + 1, next_weight, tree);
        }
        if (recorder) recorder->end(seen);
        colour += factor * seen;
    };
    if (colours.reflectivity > 0)
        follow(RayKind::reflection, colours.reflectivity,
               [&] { return reflected_ray(ray, surface); });
    if (m.transmission > 0)
        follow(RayKind::transmission, m.transmission,
               [&] { return transmitted_ray(ray, surface, m.ior); });
    return colour;
}

} // namespace GLINT_PRECISION
} // namespace glint
