// The cone of radius r(y) = 1 − y·(1 − top_radius), 0 ≤ y ≤ 1: part 0 the slanted side, 1 the
// base disk at y = 0, 2 the top disk at y = 1 (only when top_radius > 0). An open cone (NFF's `c`,
// a truncated cone of any two radii) has no disks.
#pragma once

#include "trace/shapes/cylinder.h"

#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {

inline ShapeHit intersect_cone(const Ray& ray, Real top_radius, Real t_max, bool open = false) {
    // x² + z² = (1 − k·y)², k = 1 − top_radius. The quadratic has no closest-approach form like
    // the sphere's, so it is solved in double: cones are few and b² − ac then keeps its digits.
    const double k = 1.0 - top_radius;
    const DVec3 o(ray.origin);
    const DVec3 d(ray.direction);
    const double w = 1.0 - k * o.y;
    const double wd = -k * d.y;
    const double a = d.x * d.x + d.z * d.z - wd * wd;
    const double b = o.x * d.x + o.z * d.z - w * wd;
    const double c = o.x * o.x + o.z * o.z - w * w;
    ShapeHit best;
    auto side = [&](double t) {
        const double y = o.y + t * d.y;
        if (y >= 0.0 && y <= 1.0) best = closer(best, candidate(static_cast<Real>(t), t_max, 0));
    };
    if (a == 0) {
        if (b != 0) side(-c / (2 * b)); // parallel to a slant line: one crossing
    } else {
        const double discriminant = b * b - a * c;
        if (discriminant >= 0) {
            const double q = -(b + std::copysign(std::sqrt(discriminant), b));
            if (q != 0) side(c / q);
            side(q / a);
        }
    }
    if (open) return best;
    best = closer(best, intersect_cap(ray, 0.0_r, 1.0_r, t_max, 1));
    if (top_radius > 0) best = closer(best, intersect_cap(ray, 1.0_r, top_radius, t_max, 2));
    return best;
}

inline SurfaceSample cone_surface(Vec3 p, std::uint32_t part, Real top_radius) {
    if (part != 0) return cap_surface(p, part);
    const Real k = 1.0_r - top_radius;
    const Real radius = 1.0_r - k * p.y;
    const Real rho = std::sqrt(p.x * p.x + p.z * p.z);
    const Vec3 on_side = rho > 0 ? Vec3(p.x * radius / rho, p.y, p.z * radius / rho) : p;
    // Gradient of x² + z² − (1 − k·y)²; at the apex (radius 0) the axis is the best normal.
    const Vec3 gradient(on_side.x, k * radius, on_side.z);
    const Real length = glm::length(gradient);
    const Vec3 normal = length > 0 ? gradient / length : Vec3(0.0_r, 1.0_r, 0.0_r);
    // y carries o + t·d's error (γ3); the radial projection adds γ5 and passes y's error on
    // through r(y), scaled by |k|.
    const Real y_error = gamma(3) * std::abs(p.y);
    const Vec3 error(gamma(5) * std::abs(on_side.x) + std::abs(k) * y_error, y_error,
                     gamma(5) * std::abs(on_side.z) + std::abs(k) * y_error);
    return {on_side, normal, error};
}

// The cone in the shape table (trace/shapes/table.h).
struct Cone {
    static constexpr std::string_view name = "cone";
    static constexpr ShapeTraits traits{.convex = true, .keys = {.top_radius = true, .open = true}};

    static ObjectBox bounds(const SceneObject& object, const std::vector<TriangleMesh>&) {
        const double r = std::max(1.0, double(object.top_radius));
        return {DVec3(-r, 0.0, -r), DVec3(r, 1.0, r)};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams& shape, const Ray& ray, Real t_max, Counters&) {
        return intersect_cone(ray, shape.top_radius, t_max, shape.open);
    }
    static SurfaceSample surface(const ShapeParams& shape, Vec3 p, const Hit& hit) {
        return cone_surface(p, hit.primitive, shape.top_radius);
    }
    static Tessellation tessellate(float top_radius, bool open, int n) {
        return tessellate_frustum(top_radius, open, n);
    }
};

} // namespace GLINT_PRECISION
} // namespace glint
