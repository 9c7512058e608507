// The SIMD kernels answer exactly what the single tests they stand for answer, bit for bit, on
// millions of random cases built to hit their corners: rays through vertices and edges (where
// the watertight test falls back to double), rays in a triangle's plane, degenerate triangles
// (repeated corners, collinear, zero area), tiny and huge coordinates, and blocks of every fill.
#include "test_scenes.h"

#include "trace/shapes/mesh.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>

namespace glint {
namespace {

// Equal to the bit (NaN included, as the same NaN).
::testing::AssertionResult same_hit(const TriangleHit& got, const TriangleHit& expected) {
    if (std::bit_cast<std::uint32_t>(static_cast<float>(got.t)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.t)) &&
        std::bit_cast<std::uint32_t>(static_cast<float>(got.u)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.u)) &&
        std::bit_cast<std::uint32_t>(static_cast<float>(got.v)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.v)))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "got t " << got.t << " u " << got.u << " v " << got.v << ", expected t " << expected.t
           << " u " << expected.u << " v " << expected.v;
}

// A random triangle of one of several kinds, at a random scale and offset.
std::array<Vec3, 3> random_triangle(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    std::array<Vec3, 3> p{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                          Vec3(u(rng), u(rng), u(rng))};
    switch (rng() % 8) {
    case 0: // two corners the same
        p[rng() % 3] = p[(rng() % 2) + 1 == 1 ? 0 : 1];
        break;
    case 1: // collinear
        p[2] = p[0] + 0.5f * (p[1] - p[0]);
        break;
    case 2: // on an integer lattice, sharing planes and edges with its neighbours
        for (Vec3& c : p) c = glm::round(4.0f * c);
        break;
    case 3: // axis-aligned plane
        p[0].y = p[1].y = p[2].y = 0.25f;
        break;
    default:
        break;
    }
    static constexpr float kScales[] = {1e-6f, 1e-3f, 1, 1e3f, 1e6f};
    const float scale = kScales[rng() % 5];
    const Vec3 offset =
        rng() % 3 == 0 ? Vec3(1e5f * u(rng), 1e5f * u(rng), 1e5f * u(rng)) : Vec3(0.0f);
    for (Vec3& c : p) c = c * scale + offset;
    return p;
}

// A ray aimed at a point of the triangle that decides watertightness (a corner, an edge's
// midpoint), inside it, or past it; or lying in its plane (grazing); or axis-parallel.
Ray ray_at(const std::array<Vec3, 3>& p, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1), w(0, 1);
    const float size = glm::length(p[1] - p[0]) + glm::length(p[2] - p[0]) + 1e-30f;
    Vec3 target;
    switch (rng() % 5) {
    case 0:
        target = p[rng() % 3];
        break;
    case 1:
        target = 0.5f * (p[rng() % 3] + p[rng() % 3]);
        break;
    case 2: {
        const float a = w(rng), b = w(rng) * (1 - a);
        target = p[0] + a * (p[1] - p[0]) + b * (p[2] - p[0]);
        break;
    }
    default:
        target = p[0] + size * Vec3(u(rng), u(rng), u(rng));
        break;
    }
    Vec3 origin = target + 3.0f * size * Vec3(u(rng), u(rng), u(rng));
    switch (rng() % 6) {
    case 0: // in the triangle's plane (as nearly as float puts it)
        origin = p[0] + 2.0f * (p[0] - target);
        break;
    case 1: // axis-parallel
        origin = target, origin[rng() % 3] += (rng() % 2 ? 1.0f : -1.0f) * 3 * size;
        break;
    default:
        break;
    }
    Vec3 direction = target - origin;
    if (direction == Vec3(0.0f)) direction = {0, 0, 1};
    return {origin, direction};
}

// intersect_triangles (a block of up to four triangles against one ray) against
// intersect_triangle lane by lane: 4 million rays in Release, each at one of its block's
// triangles, so that the corner cases are met in every lane.
TEST(Kernel, TriangleBlocksAgreeExactlyWithTheSingleTest) {
    std::mt19937 rng(7);
    const int blocks = testing::kUnderSanitizers ? 20000 : 200000;
    std::uint64_t hits = 0, edge_cases = 0, tests = 0;
    for (int b = 0; b < blocks; ++b) {
        const std::uint32_t lanes = 1 + rng() % kTriangleLanes;
        TriangleBlock block{};
        std::array<Vec3, 3> triangles[kTriangleLanes];
        for (std::uint32_t i = 0; i < lanes; ++i) {
            triangles[i] = i > 0 && rng() % 4 == 0 ? triangles[i - 1] : random_triangle(rng);
            if (i > 0 && rng() % 4 == 0) // a neighbour: shares an edge with the one before
                triangles[i][2] = triangles[i - 1][0] + triangles[i - 1][1] - triangles[i - 1][2];
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a) block.p[k][a][i] = triangles[i][k][a];
        }
        for (int r = 0; r < 20; ++r) {
            const WatertightRay ray(ray_at(triangles[rng() % lanes], rng));
            TriangleHit got[kTriangleLanes];
            intersect_triangles(block, lanes, ray, got);
            for (std::uint32_t i = 0; i < lanes; ++i) {
                const std::array<Vec3, 3>& t = triangles[i];
                const TriangleHit expected = intersect_triangle(t[0], t[1], t[2], ray);
                ASSERT_TRUE(same_hit(got[i], expected))
                    << "block " << b << " ray " << r << " lane " << i;
                ++tests;
                hits += expected.t < kInfinity;
                edge_cases += expected.u == 0 || expected.v == 0;
            }
        }
    }
    EXPECT_GT(hits, tests / 5) << "too few hits to mean much";
    EXPECT_GT(edge_cases, tests / 100) << "too few rays through edges and corners";
}

} // namespace
} // namespace glint
