// Triangles and indexed triangle meshes (counter-clockwise front), in object space.
#pragma once

#include "trace/shapes/shape.h"

#include <vector>

namespace glint {

struct Bounds {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    void extend(Vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
};

// Slab test of a ray (with precomputed 1/direction) against a box over (0, t_max). Conservative:
// the far distance is enlarged by 2γ3 (pbrt-v4, Bounds3::IntersectP), and NaNs from 0·inf at a
// slab's edge never reject.
inline bool hits_bounds(const Bounds& b, const Ray& ray, Vec3 inverse_direction, float t_max) {
    float t_near = 0.0f, t_far = t_max;
    for (int axis = 0; axis < 3; ++axis) {
        float t0 = (b.lo[axis] - ray.origin[axis]) * inverse_direction[axis];
        float t1 = (b.hi[axis] - ray.origin[axis]) * inverse_direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= 1.0f + 2.0f * gamma(3);
        if (t0 > t_near) t_near = t0;
        if (t1 < t_far) t_far = t1;
        if (t_near > t_far) return false;
    }
    return true;
}

struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles; // indices into vertices
    Bounds bounds;                     // of the vertices, object space
};

struct TriangleHit {
    float t = kInfinity;
    float u = 0, v = 0; // barycentric weights of vertices 1 and 2
};

// Möller–Trumbore. Hits on a shared edge may be found by both triangles or, through rounding,
// by neither; a watertight test (Woop et al. 2013) is the planned replacement.
inline TriangleHit intersect_triangle(Vec3 p0, Vec3 p1, Vec3 p2, const Ray& ray) {
    const Vec3 e1 = p1 - p0;
    const Vec3 e2 = p2 - p0;
    const Vec3 pv = glm::cross(ray.direction, e2);
    const float det = glm::dot(e1, pv);
    if (det == 0) return {};
    const float inverse_det = 1.0f / det;
    const Vec3 tv = ray.origin - p0;
    const float u = glm::dot(tv, pv) * inverse_det;
    if (!(u >= 0.0f && u <= 1.0f)) return {};
    const Vec3 qv = glm::cross(tv, e1);
    const float v = glm::dot(ray.direction, qv) * inverse_det;
    if (!(v >= 0.0f && u + v <= 1.0f)) return {};
    return {glm::dot(e2, qv) * inverse_det, u, v};
}

inline ShapeHit intersect_mesh(const Mesh& mesh, const Ray& ray, float t_max) {
    if (!hits_bounds(mesh.bounds, ray, 1.0f / ray.direction, t_max)) return {};
    ShapeHit best;
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3 tri = mesh.triangles[i];
        const TriangleHit h = intersect_triangle(mesh.vertices[tri.x], mesh.vertices[tri.y],
                                                 mesh.vertices[tri.z], ray);
        best = closer(best, candidate(h.t, glm::min(t_max, best.t), i));
    }
    return best;
}

inline SurfaceSample mesh_surface(const Mesh& mesh, const Ray& ray, std::uint32_t triangle) {
    const glm::uvec3 tri = mesh.triangles[triangle];
    const Vec3 p0 = mesh.vertices[tri.x], p1 = mesh.vertices[tri.y], p2 = mesh.vertices[tri.z];
    const TriangleHit h = intersect_triangle(p0, p1, p2, ray);
    const float b0 = 1.0f - h.u - h.v;
    // Barycentric interpolation keeps the point on the triangle's plane up to γ7·Σ|bᵢ·pᵢ|
    // (pbrt-v4, Triangle::InteractionFromIntersection).
    const Vec3 point = b0 * p0 + h.u * p1 + h.v * p2;
    const Vec3 error = gamma(7) * (glm::abs(b0 * p0) + glm::abs(h.u * p1) + glm::abs(h.v * p2));
    return {point, glm::normalize(glm::cross(p1 - p0, p2 - p0)), error};
}

} // namespace glint
