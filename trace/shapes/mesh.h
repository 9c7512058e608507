// Triangles and indexed triangle meshes (counter-clockwise front), in object space.
#pragma once

#include "trace/accel/bvh.h"
#include "trace/bounds.h"
#include "trace/shapes/shape.h"

#include <vector>

namespace glint {

struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles; // indices into vertices
    Bounds bounds;                     // of the vertices, object space
    Bvh bvh;                           // over the triangles, object space; built by World
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

// The nearest triangle: through the mesh's own BVH (the bottom level of a two-level structure),
// or, for meshes too small to have one, all of them.
template <class Counters>
ShapeHit intersect_mesh(const Mesh& mesh, const Ray& ray, float t_max, Counters& counters) {
    ShapeHit best;
    const auto test = [&](std::uint32_t i, float& limit) {
        const glm::uvec3 tri = mesh.triangles[i];
        const TriangleHit h = intersect_triangle(mesh.vertices[tri.x], mesh.vertices[tri.y],
                                                 mesh.vertices[tri.z], ray);
        if (h.t > 0 && h.t < limit && h.t < best.t) best = {h.t, i}, limit = h.t;
        return false;
    };
    float limit = t_max;
    if (!mesh.bvh.nodes().empty()) {
        mesh.bvh.traverse(ray, limit, counters, test);
    } else {
        if (!hits_bounds(mesh.bounds, ray, 1.0f / ray.direction, t_max)) return {};
        for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i)
            counters.primitive(), test(i, limit);
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
