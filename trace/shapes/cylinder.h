// The cylinder x²+z² = 1, 0 ≤ y ≤ 1: part 0 the side (radial normal), 1 the cap at y = 0
// (normal −y), 2 the cap at y = 1 (normal +y). An open cylinder (NFF's `c`) has no caps.
#pragma once

#include "trace/shapes/shape.h"

#include <cmath>
#include <utility>

namespace glint {
inline namespace GLINT_PRECISION {

// Where the ray crosses the horizontal disk y = height, x²+z² ≤ radius²: t, or NaN where it
// passes outside (or never reaches the plane: a NaN x²+z² counts as inside, t being NaN then
// or infinite).
inline Real cap_crossing(const Ray& ray, Real height, Real radius) {
    const Real t = (height - ray.origin.y) / ray.direction.y;
    const Real x = ray.origin.x + t * ray.direction.x;
    const Real z = ray.origin.z + t * ray.direction.z;
    return x * x + z * z > radius * radius ? kNaN : t;
}

// A hit on that disk.
inline ShapeHit intersect_cap(const Ray& ray, Real height, Real radius, Real t_max,
                              std::uint32_t part) {
    return candidate(cap_crossing(ray, height, radius), t_max, part);
}

// Where a ray crosses the cylinder, in the order its hit prefers them on equal t: the side's
// two roots (nearer first), the cap at y = 0, the cap at y = 1; NaN where it does not. These
// depend on the ray alone, so four cylinders' are computed at once (cylinder_crossings4) and
// each lane's hit picked below t_max afterwards (cylinder_hit).
struct CylinderCrossings {
    Real t[4];
};

inline CylinderCrossings cylinder_crossings(const Ray& ray, bool open) {
    const Vec3 o = ray.origin;
    const Vec3 d = ray.direction;
    CylinderCrossings crossings{{kNaN, kNaN, kNaN, kNaN}};
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
            const Real roots[2] = {c / q, q / a};
            for (int i = 0; i < 2; ++i) {
                const Real y = o.y + roots[i] * d.y;
                if (y >= 0.0_r && y <= 1.0_r) crossings.t[i] = roots[i];
            }
        }
    }
    if (!open) {
        crossings.t[2] = cap_crossing(ray, 0.0_r, 1.0_r);
        crossings.t[3] = cap_crossing(ray, 1.0_r, 1.0_r);
    }
    return crossings;
}

// The first crossing in (0, t_max): part 0 the side, 1 and 2 the caps; the earlier on equal t.
inline ShapeHit cylinder_hit(const CylinderCrossings& crossings, Real t_max, bool open) {
    ShapeHit best =
        closer(candidate(crossings.t[0], t_max, 0), candidate(crossings.t[1], t_max, 0));
    if (open) return best;
    best = closer(best, candidate(crossings.t[2], t_max, 1));
    return closer(best, candidate(crossings.t[3], t_max, 2));
}

inline ShapeHit intersect_cylinder(const Ray& ray, Real t_max, bool open = false) {
    return cylinder_hit(cylinder_crossings(ray, open), t_max, open);
}

// cylinder_crossings (with caps) for four rays, each in its own cylinder's object space:
// crossings[i] for lane i, bit for bit. In SSE, its operations in the same order lane by lane,
// each lane's branches as masks; elsewhere, lane by lane.
inline void cylinder_crossings4(const Rays4& rays, CylinderCrossings (&crossings)[4]) {
#if GLINT_SIMD
    const __m128 ox = _mm_load_ps(rays.origin[0]), oy = _mm_load_ps(rays.origin[1]),
                 oz = _mm_load_ps(rays.origin[2]);
    const __m128 dx = _mm_load_ps(rays.direction[0]), dy = _mm_load_ps(rays.direction[1]),
                 dz = _mm_load_ps(rays.direction[2]);
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), nan = _mm_set1_ps(kNaN);
    const auto square_sum = [](__m128 x, __m128 z) {
        return _mm_add_ps(_mm_mul_ps(x, x), _mm_mul_ps(z, z));
    };
    const auto keep = [nan](__m128 mask, __m128 t) {
        return _mm_or_ps(_mm_and_ps(mask, t), _mm_andnot_ps(mask, nan));
    };
    alignas(16) Real t[4][4];
    // The side.
    const __m128 a = square_sum(dx, dz);
    const __m128 b = _mm_add_ps(_mm_mul_ps(ox, dx), _mm_mul_ps(oz, dz));
    const __m128 c = _mm_sub_ps(square_sum(ox, oz), one);
    const __m128 k = _mm_div_ps(b, a);
    const __m128 cx = _mm_sub_ps(ox, _mm_mul_ps(k, dx));
    const __m128 cz = _mm_sub_ps(oz, _mm_mul_ps(k, dz));
    const __m128 discriminant = _mm_mul_ps(a, _mm_sub_ps(one, square_sum(cx, cz)));
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 root =
        _mm_or_ps(_mm_andnot_ps(sign, _mm_sqrt_ps(discriminant)), _mm_and_ps(sign, b));
    const __m128 q = _mm_xor_ps(_mm_add_ps(b, root), sign);
    const __m128 crosses = _mm_and_ps(_mm_cmpgt_ps(a, zero), _mm_cmpge_ps(discriminant, zero));
    const __m128 roots[2] = {_mm_div_ps(c, q), _mm_div_ps(q, a)};
    for (int i = 0; i < 2; ++i) {
        const __m128 y = _mm_add_ps(oy, _mm_mul_ps(roots[i], dy));
        const __m128 within = _mm_and_ps(_mm_cmpge_ps(y, zero), _mm_cmple_ps(y, one));
        _mm_store_ps(t[i], keep(_mm_and_ps(crosses, within), roots[i]));
    }
    // The caps: radius 1, so radius² = 1.
    const __m128 heights[2] = {zero, one};
    for (int i = 0; i < 2; ++i) {
        const __m128 cap = _mm_div_ps(_mm_sub_ps(heights[i], oy), dy);
        const __m128 x = _mm_add_ps(ox, _mm_mul_ps(cap, dx));
        const __m128 z = _mm_add_ps(oz, _mm_mul_ps(cap, dz));
        _mm_store_ps(t[2 + i], keep(_mm_cmpngt_ps(square_sum(x, z), one), cap));
    }
    for (int lane = 0; lane < 4; ++lane)
        for (int i = 0; i < 4; ++i) crossings[lane].t[i] = t[i][lane];
#else
    for (int lane = 0; lane < 4; ++lane)
        crossings[lane] = cylinder_crossings(rays.lane(lane), false);
#endif
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
