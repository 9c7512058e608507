#include "raster/tessellation.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Builder {
    Tessellation mesh;

    std::uint32_t vertex(DVec3 p) {
        mesh.vertices.push_back(Vec3(p));
        return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
    }
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const Vec3 p0 = mesh.vertices[a], p1 = mesh.vertices[b], p2 = mesh.vertices[c];
        if (glm::length(glm::cross(p1 - p0, p2 - p0)) > 0) mesh.triangles.push_back({a, b, c});
    }
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }
};

// A ring of `n` vertices at height y whose polygon circumscribes the circle of radius r: its
// edges touch the circle at their midpoints, so every side face built on it is tangent.
std::vector<std::uint32_t> ring(Builder& b, int n, double y, double r) {
    const double circumscribed = r / std::cos(kPi / n);
    std::vector<std::uint32_t> ids;
    for (int i = 0; i < n; ++i) {
        const double phi = 2 * kPi * i / n;
        ids.push_back(b.vertex({circumscribed * std::cos(phi), y, circumscribed * std::sin(phi)}));
    }
    return ids;
}

void cap(Builder& b, const std::vector<std::uint32_t>& rim, double y) {
    const std::uint32_t centre = b.vertex({0, y, 0});
    for (std::size_t i = 0; i < rim.size(); ++i)
        b.triangle(centre, rim[i], rim[(i + 1) % rim.size()]);
}

Tessellation sphere(int n) {
    const int bands = std::max(2, n / 2);
    Builder b;
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
    // Latitude-longitude quads are planar (isosceles trapezoids). Push every vertex out by the
    // factor that moves the nearest face plane to distance 1 from the centre: then every face
    // lies outside the unit sphere, and the vertices, at that factor, deviate most.
    double nearest = 1;
    for (const glm::uvec3& t : b.mesh.triangles) {
        const DVec3 p0(b.mesh.vertices[t.x]), p1(b.mesh.vertices[t.y]), p2(b.mesh.vertices[t.z]);
        const DVec3 normal = glm::cross(p1 - p0, p2 - p0);
        if (glm::length(normal) > 0)
            nearest = std::min(nearest, std::abs(glm::dot(glm::normalize(normal), p0)));
    }
    const double scale = 1 / nearest * (1 + 1e-6); // and a little more for the float rounding
    for (Vec3& v : b.mesh.vertices) v = Vec3(DVec3(v) * scale);
    b.mesh.max_deviation = static_cast<float>(scale - 1);
    return b.mesh;
}

} // namespace

Tessellation tessellate(ShapeKind shape, float top_radius, int level, bool open) {
    const int n = std::clamp(level, kMinTessellation, kMaxTessellation);
    // Circumscribed polygons with float rounding allowed for.
    const double outward = 1 / std::cos(kPi / n) * (1 + 1e-6);
    Builder b;
    switch (shape) {
    case ShapeKind::sphere:
        return sphere(n);
    case ShapeKind::box: {
        for (int corner = 0; corner < 8; ++corner)
            b.vertex({corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0});
        const std::uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
        for (const auto& f : faces) b.quad(f[0], f[1], f[2], f[3]);
        return b.mesh; // exact
    }
    case ShapeKind::disk: {
        cap(b, ring(b, n, 0, 1 * (1 + 1e-6)), 0);
        b.mesh.max_deviation = static_cast<float>(outward - 1);
        return b.mesh;
    }
    case ShapeKind::cylinder:
    case ShapeKind::cone: {
        const double top = shape == ShapeKind::cylinder ? 1.0 : top_radius;
        const auto bottom = ring(b, n, 0, 1 * (1 + 1e-6));
        if (top > 0) {
            const auto upper = ring(b, n, 1, top * (1 + 1e-6));
            for (int i = 0; i < n; ++i)
                b.quad(bottom[i], upper[i], upper[(i + 1) % n], bottom[(i + 1) % n]);
            if (!open) cap(b, upper, 1);
        } else {
            const std::uint32_t apex = b.vertex({0, 1, 0});
            for (int i = 0; i < n; ++i) b.triangle(bottom[i], apex, bottom[(i + 1) % n]);
        }
        if (!open) cap(b, bottom, 0);
        b.mesh.max_deviation = static_cast<float>((outward - 1) * std::max(1.0, top));
        return b.mesh;
    }
    case ShapeKind::plane:
    case ShapeKind::triangle:
    case ShapeKind::mesh:
        break;
    }
    return b.mesh;
}

} // namespace glint
