// What the shapes' conservative tessellations (their `tessellate`, trace/shapes/table.h) are
// built with: triangle meshes that enclose the unit primitive, so that along any ray the mesh is
// hit no later than the surface, which is what the item buffer's exact resolve relies on
// (trace/primary_hits.cpp). Double arithmetic, float vertices: the same in both precisions.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace glint {

inline constexpr double kPi = 3.14159265358979323846;

struct Tessellation {
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles;
    // Object space: no point of the mesh is farther than this from the true surface.
    float max_deviation = 0.0f;
};

struct TessellationBuilder {
    Tessellation mesh;

    std::uint32_t vertex(glm::dvec3 p) {
        mesh.vertices.push_back(glm::vec3(p));
        return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
    }
    // Zero-area triangles (a sphere's poles, a cone's apex) are dropped.
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const glm::vec3 p0 = mesh.vertices[a], p1 = mesh.vertices[b], p2 = mesh.vertices[c];
        if (glm::length(glm::cross(p1 - p0, p2 - p0)) > 0) mesh.triangles.push_back({a, b, c});
    }
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }

    // A ring of `n` vertices at height y whose polygon circumscribes the circle of radius r: its
    // edges touch the circle at their midpoints, so every side face built on it is tangent.
    std::vector<std::uint32_t> ring(int n, double y, double r) {
        const double circumscribed = r / std::cos(kPi / n);
        std::vector<std::uint32_t> ids;
        for (int i = 0; i < n; ++i) {
            const double phi = 2 * kPi * i / n;
            ids.push_back(
                vertex({circumscribed * std::cos(phi), y, circumscribed * std::sin(phi)}));
        }
        return ids;
    }

    // A fan closing `rim` at height y.
    void cap(const std::vector<std::uint32_t>& rim, double y) {
        const std::uint32_t centre = vertex({0, y, 0});
        for (std::size_t i = 0; i < rim.size(); ++i)
            triangle(centre, rim[i], rim[(i + 1) % rim.size()]);
    }
};

// How far a polygon of n sides circumscribing the unit circle reaches (its corners), with float
// rounding allowed for.
inline double circumscribed_reach(int n) {
    return 1 / std::cos(kPi / n) * (1 + 1e-6);
}

} // namespace glint
