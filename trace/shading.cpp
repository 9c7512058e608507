#include "trace/shading.h"

#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {

Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, Real weight,
           RayCounts& counts, Real& omitted_weight) {
    if (!hit.found()) return world.background();
    return shade(world, ray, hit, world.surface(ray, hit), depth, weight, counts, omitted_weight);
}

Vec3 shade(const World& world, const Ray& ray, const Hit& hit, const SurfacePoint& surface,
           int depth, Real weight, RayCounts& counts, Real& omitted_weight) {
    const Phong& m = world.material(hit.object);
    const Vec3 n = surface.shading;
    const Vec3 v = -glm::normalize(ray.direction);
    const Vec3 origin = surface.spawn();

    Vec3 colour = m.ambient * world.ambient();
    for (const Light& light : world.lights()) {
        const Vec3 l = glm::normalize(light.position - surface.position);
        const Real n_dot_l = glm::dot(n, l);
        if (n_dot_l <= 0) continue; // the light is behind the surface
        ++counts.shadow;
        // Hard shadows: anything on the open segment from the point to the light (t in (0, 1)).
        if (world.occluded({origin, light.position - origin}, 1.0_r, surface.skip)) continue;
        Vec3 lit = m.diffuse * n_dot_l;
        if (m.specular != Vec3(0.0_r)) { // pow is dear, and NFF's matte surfaces have 1e5
            const Vec3 r = 2.0_r * n * n_dot_l - l; // reflect(−l, n)
            lit += m.specular * std::pow(glm::max(0.0_r, glm::dot(r, v)), m.shininess);
        }
        colour += light.color * lit;
    }

    // Perfect reflection, cast only while it can still matter: below max_depth, and while the
    // path weight (this surface's reflectivity included) stays at or above min_reflectivity.
    const RenderSettings& settings = world.settings();
    const Real reflected_weight = weight * m.reflectivity;
    if (m.reflectivity <= 0) return colour;
    if (depth < settings.max_depth && reflected_weight >= settings.min_reflectivity) {
        ++counts.reflection;
        const Ray reflection{origin, reflect(ray.direction, n)};
        const Hit next = world.intersect(reflection, kInfinity, surface.skip);
        colour += m.reflectivity * shade(world, reflection, next, depth + 1, reflected_weight,
                                         counts, omitted_weight);
    } else {
        omitted_weight = reflected_weight;
    }
    return colour;
}

} // namespace GLINT_PRECISION
} // namespace glint
