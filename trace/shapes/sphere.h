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
