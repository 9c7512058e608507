// The unit sphere x²+y²+z² = 1, outward normal p.
#pragma once

#include "trace/shapes/shape.h"

#include <cmath>
#include <utility>

namespace glint {
inline namespace GLINT_PRECISION {

// Solves |o + t·d|² = 1 without catastrophic cancellation (Ray Tracing Gems ch. 7, Haines et
// al.): the discriminant b² − ac is computed as a·(1 − |o − (b/a)·d|²), the squared distance of
// the closest approach, and the roots as q/a and c/q with q = −(b + sign(b)·√Δ). A small sphere
// far from the origin stays round instead of turning blocky or vanishing.
inline ShapeHit intersect_sphere(const Ray& ray, Real t_max) {
    const Vec3 o = ray.origin;
    const Vec3 d = ray.direction;
    const Real a = glm::dot(d, d);
    const Real b = glm::dot(o, d); // half of the textbook b
    const Real c = glm::dot(o, o) - 1.0_r;
    const Vec3 closest = o - (b / a) * d;
    const Real discriminant = a * (1.0_r - glm::dot(closest, closest));
    if (discriminant < 0) return {};
    const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
    Real t0 = c / q;
    Real t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    const ShapeHit near = candidate(t0, t_max, 0);
    return near.found() ? near : candidate(t1, t_max, 0);
}

inline SurfaceSample sphere_surface(Vec3 p) {
    // Projecting onto the sphere leaves an error of γ5·|p| (pbrt-v4, Sphere::Intersect).
    const Vec3 on_sphere = p / glm::length(p);
    return {on_sphere, on_sphere, gamma(5) * glm::abs(on_sphere)};
}

} // namespace GLINT_PRECISION
} // namespace glint
