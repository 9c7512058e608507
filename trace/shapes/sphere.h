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
// The roots, nearer first; `missed` when the discriminant is negative.
struct SphereRoots {
    Real t0, t1;
    bool missed;
};
inline SphereRoots sphere_roots(const Ray& ray) {
    const Vec3 o = ray.origin;
    const Vec3 d = ray.direction;
    const Real a = glm::dot(d, d);
    const Real b = glm::dot(o, d); // half of the textbook b
    const Real c = glm::dot(o, o) - 1.0_r;
    const Vec3 closest = o - (b / a) * d;
    const Real discriminant = a * (1.0_r - glm::dot(closest, closest));
    if (discriminant < 0) return {0, 0, true};
    const Real q = -(b + std::copysign(std::sqrt(discriminant), b));
    Real t0 = c / q;
    Real t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    return {t0, t1, false};
}

// The sphere's first hit in (0, t_max) from its roots.
inline ShapeHit sphere_hit(const SphereRoots& roots, Real t_max) {
    if (roots.missed) return {};
    const ShapeHit near = candidate(roots.t0, t_max, 0);
    return near.found() ? near : candidate(roots.t1, t_max, 0);
}

inline ShapeHit intersect_sphere(const Ray& ray, Real t_max) {
    return sphere_hit(sphere_roots(ray), t_max);
}

// Four spheres placed without rotation or shear at once: sphere i's object space is
// (p − offset_i)·inverse_scale_i (Transform::to_object for identity, translation and uniform
// scale: an identity or translation has inverse_scale 1, exactly as it maps). roots[i] =
// sphere_roots(the ray in sphere i's object space), bit for bit: in SSE, sphere_roots'
// operations in the same order lane by lane (the divisions and the square root, which dominate,
// four an instruction); elsewhere (double precision), one sphere at a time. Reads four entries
// of each array from `first`, whatever lanes the caller uses.
inline void sphere_roots4(const Ray& ray, const Real* x, const Real* y, const Real* z,
                          const Real* inverse_scale, SphereRoots (&roots)[4]) {
#if GLINT_SIMD
    const __m128 inv = _mm_loadu_ps(inverse_scale);
    const __m128 ox = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(ray.origin.x), _mm_loadu_ps(x)), inv);
    const __m128 oy = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(ray.origin.y), _mm_loadu_ps(y)), inv);
    const __m128 oz = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(ray.origin.z), _mm_loadu_ps(z)), inv);
    const __m128 dx = _mm_mul_ps(_mm_set1_ps(ray.direction.x), inv);
    const __m128 dy = _mm_mul_ps(_mm_set1_ps(ray.direction.y), inv);
    const __m128 dz = _mm_mul_ps(_mm_set1_ps(ray.direction.z), inv);
    const auto dot = [](__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
        return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
    };
    const __m128 one = _mm_set1_ps(1.0f);
    const __m128 a = dot(dx, dy, dz, dx, dy, dz);
    const __m128 b = dot(ox, oy, oz, dx, dy, dz);
    const __m128 c = _mm_sub_ps(dot(ox, oy, oz, ox, oy, oz), one);
    const __m128 k = _mm_div_ps(b, a);
    const __m128 cx = _mm_sub_ps(ox, _mm_mul_ps(k, dx));
    const __m128 cy = _mm_sub_ps(oy, _mm_mul_ps(k, dy));
    const __m128 cz = _mm_sub_ps(oz, _mm_mul_ps(k, dz));
    const __m128 discriminant = _mm_mul_ps(a, _mm_sub_ps(one, dot(cx, cy, cz, cx, cy, cz)));
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 root =
        _mm_or_ps(_mm_andnot_ps(sign, _mm_sqrt_ps(discriminant)), _mm_and_ps(sign, b));
    const __m128 q = _mm_xor_ps(_mm_add_ps(b, root), sign);
    const __m128 near = _mm_div_ps(c, q), far = _mm_div_ps(q, a);
    const __m128 swap = _mm_cmpgt_ps(near, far);
    alignas(16) Real t0[4], t1[4];
    _mm_store_ps(t0, _mm_or_ps(_mm_and_ps(swap, far), _mm_andnot_ps(swap, near)));
    _mm_store_ps(t1, _mm_or_ps(_mm_and_ps(swap, near), _mm_andnot_ps(swap, far)));
    const unsigned missed =
        static_cast<unsigned>(_mm_movemask_ps(_mm_cmplt_ps(discriminant, _mm_setzero_ps())));
    for (int i = 0; i < 4; ++i) roots[i] = {t0[i], t1[i], ((missed >> i) & 1) != 0};
#else
    for (int i = 0; i < 4; ++i) {
        const Ray local{(ray.origin - Vec3(x[i], y[i], z[i])) * inverse_scale[i],
                        ray.direction * inverse_scale[i]};
        roots[i] = sphere_roots(local);
    }
#endif
}

inline SurfaceSample sphere_surface(Vec3 p) {
    // Projecting onto the sphere leaves an error of γ5·|p| (pbrt-v4, Sphere::Intersect).
    const Vec3 on_sphere = p / glm::length(p);
    return {on_sphere, on_sphere, gamma(5) * glm::abs(on_sphere)};
}

// The sphere in the shape table (trace/shapes/table.h).
struct Sphere {
    static constexpr std::string_view name = "sphere";
    static constexpr ShapeTraits traits{.convex = true, .keys = {}};

    static ObjectBox bounds(const SceneObject&, const std::vector<TriangleMesh>&) {
        return {DVec3(-1.0), DVec3(1.0)};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams&, const Ray& ray, Real t_max, Counters&) {
        return intersect_sphere(ray, t_max);
    }
    static SurfaceSample surface(const ShapeParams&, Vec3 p, const Hit&) {
        return sphere_surface(p);
    }

    // Latitude-longitude quads (level/2 bands), which are planar (isosceles trapezoids), with
    // every vertex pushed out by the factor that moves the nearest face plane to distance 1 from
    // the centre: then every face lies outside the unit sphere, and the vertices, at that factor,
    // deviate most.
    static Tessellation tessellate(float, bool, int n) {
        const int bands = std::max(2, n / 2);
        TessellationBuilder b;
        std::vector<std::vector<std::uint32_t>> rows;
        for (int j = 0; j <= bands; ++j) {
            const double theta = kPi * j / bands;
            std::vector<std::uint32_t> row;
            for (int i = 0; i < n; ++i) {
                const double phi = 2 * kPi * i / n;
                // The poles repeat one point n times; their zero-area triangles are dropped.
                row.push_back(b.vertex({std::sin(theta) * std::cos(phi), std::cos(theta),
                                        std::sin(theta) * std::sin(phi)}));
            }
            rows.push_back(row);
        }
        for (int j = 0; j < bands; ++j)
            for (int i = 0; i < n; ++i)
                b.quad(rows[j][i], rows[j][(i + 1) % n], rows[j + 1][(i + 1) % n], rows[j + 1][i]);
        double nearest = 1;
        for (const glm::uvec3& t : b.mesh.triangles) {
            const DVec3 p0(b.mesh.vertices[t.x]), p1(b.mesh.vertices[t.y]),
                p2(b.mesh.vertices[t.z]);
            const DVec3 normal = glm::cross(p1 - p0, p2 - p0);
            if (glm::length(normal) > 0)
                nearest = std::min(nearest, std::abs(glm::dot(glm::normalize(normal), p0)));
        }
        const double scale = 1 / nearest * (1 + 1e-6); // and a little more for the float rounding
        for (glm::vec3& v : b.mesh.vertices) v = glm::vec3(DVec3(v) * scale);
        b.mesh.max_deviation = static_cast<float>(scale - 1);
        return b.mesh;
    }
};

} // namespace GLINT_PRECISION
} // namespace glint
