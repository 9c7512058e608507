// The cylinder x²+z² = 1, 0 ≤ y ≤ 1: part 0 the side (radial normal), 1 the cap at y = 0
// (normal −y), 2 the cap at y = 1 (normal +y). An open cylinder (NFF's `c`) has no caps.
#pragma once

#include "trace/shapes/shape.h"

#include <cmath>
#include <utility>

namespace glint {
inline namespace GLINT_PRECISION {

// A hit on the horizontal disk y = height, x²+z² ≤ radius².
inline ShapeHit intersect_cap(const Ray& ray, Real height, Real radius, Real t_max,
                              std::uint32_t part) {
    const Real t = (height - ray.origin.y) / ray.direction.y;
    const Real x = ray.origin.x + t * ray.direction.x;
    const Real z = ray.origin.z + t * ray.direction.z;
    if (x * x + z * z > radius * radius) return {};
    return candidate(t, t_max, part);
}

inline ShapeHit intersect_cylinder(const Ray& ray, Real t_max, bool open = false) {
    const Vec3 o = ray.origin;
    const Vec3 d = ray.direction;
    ShapeHit best;
    // The side: the sphere's cancellation-free quadratic, in the xz plane.
    const Real a = d.x * d.x + d.z * d.z;
    if (a > 0) {
        const Real b = o.x * d.x + o.z * d.z;
        const Real c = o.x * o.x + o.z * o.z - 1.0_r;
        const Real cx = o.x - (b / a) * d.x;
        const Real cz = o.z - (b / a) * d.z;
        const Real discriminant = a * (1.0_r - (cx * cx + cz * cz));
        if (discriminant >= 0) {
            const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
            for (Real t : {c / q, q / a}) {
                const Real y = o.y + t * d.y;
                if (y >= 0.0_r && y <= 1.0_r) best = closer(best, candidate(t, t_max, 0));
            }
        }
    }
    if (open) return best;
    best = closer(best, intersect_cap(ray, 0.0_r, 1.0_r, t_max, 1));
    return closer(best, intersect_cap(ray, 1.0_r, 1.0_r, t_max, 2));
}

// The caps of cylinders and cones: y exact, normal ∓y.
inline SurfaceSample cap_surface(Vec3 p, std::uint32_t part) {
    const Real y = part == 1 ? 0.0_r : 1.0_r;
    const Vec3 normal(0.0_r, part == 1 ? -1.0_r : 1.0_r, 0.0_r);
    return {{p.x, y, p.z}, normal, gamma(3) * Vec3(std::abs(p.x), 0.0_r, std::abs(p.z))};
}

inline SurfaceSample cylinder_surface(Vec3 p, std::uint32_t part) {
    if (part != 0) return cap_surface(p, part);
    // Projected radially onto the side: γ5 as for the sphere; y stays as computed.
    const Real radius = std::sqrt(p.x * p.x + p.z * p.z);
    const Vec3 on_side(p.x / radius, p.y, p.z / radius);
    return {on_side, {on_side.x, 0.0_r, on_side.z}, gamma(5) * glm::abs(on_side)};
}

// The tessellation of a cylinder (top = 1) or cone: circumscribed rings at y = 0 and 1 (an apex
// when top = 0) joined by tangent side faces, and the caps unless `open`.
inline Tessellation tessellate_frustum(double top, bool open, int n) {
    TessellationBuilder b;
    const auto bottom = b.ring(n, 0, 1 * (1 + 1e-6));
    if (top > 0) {
        const auto upper = b.ring(n, 1, top * (1 + 1e-6));
        for (int i = 0; i < n; ++i)
            b.quad(bottom[i], upper[i], upper[(i + 1) % n], bottom[(i + 1) % n]);
        if (!open) b.cap(upper, 1);
    } else {
        const std::uint32_t apex = b.vertex({0, 1, 0});
        for (int i = 0; i < n; ++i) b.triangle(bottom[i], apex, bottom[(i + 1) % n]);
    }
    if (!open) b.cap(bottom, 0);
    b.mesh.max_deviation = static_cast<float>((circumscribed_reach(n) - 1) * std::max(1.0, top));
    return b.mesh;
}

// The cylinder in the shape table (trace/shapes/table.h).
struct Cylinder {
    static constexpr std::string_view name = "cylinder";
    static constexpr ShapeTraits traits{.convex = true, .keys = {.open = true}};

    static ObjectBox bounds(const SceneObject&, const std::vector<TriangleMesh>&) {
        return {DVec3(-1.0, 0.0, -1.0), DVec3(1.0, 1.0, 1.0)};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams& shape, const Ray& ray, Real t_max, Counters&) {
        return intersect_cylinder(ray, t_max, shape.open);
    }
    static SurfaceSample surface(const ShapeParams&, Vec3 p, const Hit& hit) {
        return cylinder_surface(p, hit.primitive);
    }
    static Tessellation tessellate(float, bool open, int n) {
        return tessellate_frustum(1.0, open, n);
    }
};

} // namespace GLINT_PRECISION
} // namespace glint
