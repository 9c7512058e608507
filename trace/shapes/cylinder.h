// The capped cylinder x²+z² = 1, 0 ≤ y ≤ 1: part 0 the side (radial normal), 1 the cap at
// y = 0 (normal −y), 2 the cap at y = 1 (normal +y).
#pragma once

#include "trace/shapes/shape.h"

#include <cmath>
#include <utility>

namespace glint {

// A hit on the horizontal disk y = height, x²+z² ≤ radius².
inline ShapeHit intersect_cap(const Ray& ray, float height, float radius, float t_max,
                              std::uint32_t part) {
    const float t = (height - ray.origin.y) / ray.direction.y;
    const float x = ray.origin.x + t * ray.direction.x;
    const float z = ray.origin.z + t * ray.direction.z;
    if (x * x + z * z > radius * radius) return {};
    return candidate(t, t_max, part);
}

inline ShapeHit intersect_cylinder(const Ray& ray, float t_max) {
    const Vec3 o = ray.origin;
    const Vec3 d = ray.direction;
    ShapeHit best;
    // The side: the sphere's cancellation-free quadratic, in the xz plane.
    const float a = d.x * d.x + d.z * d.z;
    if (a > 0) {
        const float b = o.x * d.x + o.z * d.z;
        const float c = o.x * o.x + o.z * o.z - 1.0f;
        const float cx = o.x - (b / a) * d.x;
        const float cz = o.z - (b / a) * d.z;
        const float discriminant = a * (1.0f - (cx * cx + cz * cz));
        if (discriminant >= 0) {
            const float q = -(b + std::copysign(std::sqrt(discriminant), b));
            for (float t : {c / q, q / a}) {
                const float y = o.y + t * d.y;
                if (y >= 0.0f && y <= 1.0f) best = closer(best, candidate(t, t_max, 0));
            }
        }
    }
    best = closer(best, intersect_cap(ray, 0.0f, 1.0f, t_max, 1));
    return closer(best, intersect_cap(ray, 1.0f, 1.0f, t_max, 2));
}

// The caps of cylinders and cones: y exact, normal ∓y.
inline SurfaceSample cap_surface(Vec3 p, std::uint32_t part) {
    const float y = part == 1 ? 0.0f : 1.0f;
    const Vec3 normal(0.0f, part == 1 ? -1.0f : 1.0f, 0.0f);
    return {{p.x, y, p.z}, normal, gamma(3) * Vec3(std::abs(p.x), 0.0f, std::abs(p.z))};
}

inline SurfaceSample cylinder_surface(Vec3 p, std::uint32_t part) {
    if (part != 0) return cap_surface(p, part);
    // Projected radially onto the side: γ5 as for the sphere; y stays as computed.
    const float radius = std::sqrt(p.x * p.x + p.z * p.z);
    const Vec3 on_side(p.x / radius, p.y, p.z / radius);
    return {on_side, {on_side.x, 0.0f, on_side.z}, gamma(5) * glm::abs(on_side)};
}

} // namespace glint
