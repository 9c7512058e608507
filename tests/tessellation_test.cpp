// Conservative tessellation: the mesh encloses the true surface (so the item buffer's exact
// resolve may trust its depth as a lower bound), and its stated deviation is honest.
#include "raster/tessellation.h"

#include "trace/shapes/cone.h"
#include "trace/shapes/sphere.h"

#include <gtest/gtest.h>

#include <random>

namespace glint {
namespace {

struct Case {
    ShapeKind shape;
    float top_radius;
};

void PrintTo(const Case& c, std::ostream* out) {
    *out << name_of(c.shape);
    if (c.top_radius > 0) *out << " (top_radius " << c.top_radius << ")";
}

// A point on the true unit surface from two uniform numbers.
Vec3 surface_point(ShapeKind shape, float top, float a, float b) {
    const float phi = 6.2831853f * a;
    switch (shape) {
    case ShapeKind::sphere: {
        const float z = 2 * b - 1, r = std::sqrt(1 - z * z);
        return {r * std::cos(phi), z, r * std::sin(phi)};
    }
    case ShapeKind::box: {
        Vec3 p(2 * a - 1, 2 * b - 1, 1.0f);
        return p;
    }
    case ShapeKind::disk:
        return {std::sqrt(b) * std::cos(phi), 0, std::sqrt(b) * std::sin(phi)};
    default: {
        const float y = b, r = shape == ShapeKind::cylinder ? 1.0f : 1 - y * (1 - top);
        return {r * std::cos(phi), y, r * std::sin(phi)};
    }
    }
}

class TessellationTest : public ::testing::TestWithParam<std::tuple<Case, int>> {};

TEST_P(TessellationTest, MeshEnclosesTheTrueSurfaceWithinItsStatedDeviation) {
    const auto [c, level] = GetParam();
    const Tessellation t = tessellate(c.shape, c.top_radius, level);
    ASSERT_FALSE(t.triangles.empty());
    Vec3 centre(0.0f);
    for (Vec3 v : t.vertices) centre += v / static_cast<float>(t.vertices.size());
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, 1);
    for (int k = 0; k < 2000; ++k) {
        const Vec3 p = surface_point(c.shape, c.top_radius, u(rng), u(rng));
        // Inside a convex mesh: behind every face plane (faces oriented away from the centre).
        for (const glm::uvec3& tri : t.triangles) {
            const Vec3 a = t.vertices[tri.x], b = t.vertices[tri.y], d = t.vertices[tri.z];
            Vec3 n = glm::normalize(glm::cross(b - a, d - a));
            if (glm::dot(n, a - centre) < 0) n = -n;
            ASSERT_LE(glm::dot(n, p - a), 1e-6f)
                << "surface point outside the mesh at level " << level;
        }
    }
    // Every rim vertex lies within the stated deviation of the surface (and never inside it);
    // cap centres and apexes (on the axis) lie on the true surface by construction.
    for (Vec3 v : t.vertices) {
        if (c.shape != ShapeKind::sphere && c.shape != ShapeKind::box &&
            v.x * v.x + v.z * v.z < 1e-12f)
            continue;
        float distance = 0;
        if (c.shape == ShapeKind::sphere)
            distance = glm::length(v) - 1;
        else if (c.shape == ShapeKind::disk)
            distance = glm::length(Vec3(v.x, 0, v.z)) - 1;
        else if (c.shape != ShapeKind::box) {
            const float r = c.shape == ShapeKind::cylinder ? 1.0f : 1 - v.y * (1 - c.top_radius);
            distance = glm::length(Vec3(v.x, 0, v.z)) - r;
        }
        EXPECT_LE(distance, t.max_deviation + 1e-6f);
        EXPECT_GE(distance, -1e-6f);
    }
    if (c.shape != ShapeKind::box && level >= 32) {
        EXPECT_LT(t.max_deviation, 0.02f);
    }
}

INSTANTIATE_TEST_SUITE_P(
    EveryCurvedShape, TessellationTest,
    ::testing::Combine(::testing::Values(Case{ShapeKind::sphere, 0}, Case{ShapeKind::box, 0},
                                         Case{ShapeKind::disk, 0}, Case{ShapeKind::cylinder, 0},
                                         Case{ShapeKind::cone, 0}, Case{ShapeKind::cone, 0.4f}),
                       ::testing::Values(3, 8, 32)),
    [](const auto& info) {
        const Case c = std::get<0>(info.param);
        return std::string(name_of(c.shape)) + (c.top_radius > 0 ? "_truncated" : "") + "_" +
               std::to_string(std::get<1>(info.param));
    });

TEST(Tessellation, DeviationShrinksQuadraticallyWithLevel) {
    // 1/cos(π/n) − 1 ≈ π²/(2n²): four times the segments, about a sixteenth of the deviation.
    const float coarse = tessellate(ShapeKind::cylinder, 0, 16).max_deviation;
    const float fine = tessellate(ShapeKind::cylinder, 0, 64).max_deviation;
    EXPECT_NEAR(coarse / fine, 16.0f, 1.0f);
}

} // namespace
} // namespace glint
