// Every primitive, plain and transformed (translated, rotated, non-uniformly scaled, sheared),
// hit by rays whose answers are worked out by hand; and the stable sphere far away.
#include "test_scenes.h"

#include "trace/shapes/box.h"
#include "trace/shapes/cone.h"
#include "trace/shapes/cylinder.h"
#include "trace/shapes/mesh.h"
#include "trace/shapes/plane.h"
#include "trace/shapes/sphere.h"
#include "trace/shapes/table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace glint {
namespace {

using testing::cast;
using testing::scene_at_origin;

constexpr float kT = 1e-5f; // relative: a few float roundings of t ≈ 1…10

TEST(Sphere, HitsFromOutsideAndInsideAndMisses) {
    EXPECT_NEAR(intersect_sphere({{0, 0, 5}, {0, 0, -1}}, kInfinity).t, 4.0f, kT);
    EXPECT_NEAR(intersect_sphere({{0, 0, 0}, {0, 0, -1}}, kInfinity).t, 1.0f, kT);
    EXPECT_NEAR(intersect_sphere({{0, 0, 5}, {0, 0, -2}}, kInfinity).t, 2.0f,
                kT); // t in units of d
    EXPECT_FALSE(intersect_sphere({{0, 1.01f, 5}, {0, 0, -1}}, kInfinity).found());
    EXPECT_FALSE(intersect_sphere({{0, 0, 5}, {0, 0, 1}}, kInfinity).found()); // behind
    EXPECT_FALSE(intersect_sphere({{0, 0, 5}, {0, 0, -1}}, 3.9f).found());     // beyond t_max
}

TEST(Sphere, SmallSphereFarAwayIsHitWhereItShouldBe) {
    // Radius 1 at distance 1e5: the textbook b² − 4ac loses every digit here.
    const Scene scene =
        scene_at_origin(R"([{"shape": "sphere", "transform": [{"translate": [0, 0, -1e5]}]}])");
    const World world(scene);
    const Hit centre = cast(world, Vec3(0.0f), {0, 0, -1});
    ASSERT_TRUE(centre.found());
    EXPECT_NEAR(centre.t, 1e5f - 1.0f, 1e5f * 4e-7f);
    // Rays at angle θ pass the centre at distance 1e5·sin θ: hit at 0.99, miss at 1.01.
    EXPECT_TRUE(cast(world, Vec3(0.0f), glm::normalize(Vec3(0.99e-5f, 0, -1))).found());
    EXPECT_FALSE(cast(world, Vec3(0.0f), glm::normalize(Vec3(1.01e-5f, 0, -1))).found());
}

TEST(Sphere, TangentRayGrazesWithoutNaN) {
    const ShapeHit h = intersect_sphere({{-5, 1, 0}, {1, 0, 0}}, kInfinity);
    if (h.found()) {
        EXPECT_NEAR(h.t, 5.0f, 1e-2f);
    }
    EXPECT_FALSE(std::isnan(h.t));
}

TEST(Plane, HitsFromAboveAndBelowAndIgnoresParallelRays) {
    EXPECT_NEAR(intersect_plane({{3, 5, 1}, {0, -1, 0}}, kInfinity).t, 5.0f, kT);
    EXPECT_NEAR(intersect_plane({{0, -2, 0}, {0, 0.5f, 0}}, kInfinity).t, 4.0f, kT);
    EXPECT_FALSE(intersect_plane({{0, 1, 0}, {1, 0, 0}}, kInfinity).found());
    EXPECT_FALSE(intersect_plane({{0, 0, 0}, {1, 0, 0}}, kInfinity).found()); // in the plane
}

TEST(Disk, HitsInsideTheUnitCircleOnly) {
    EXPECT_NEAR(intersect_disk({{0.5f, 2, 0.5f}, {0, -1, 0}}, kInfinity).t, 2.0f, kT);
    EXPECT_FALSE(intersect_disk({{0.8f, 2, 0.8f}, {0, -1, 0}}, kInfinity).found());
}

TEST(Box, ReportsTheFaceItEntersOrLeaves) {
    const ShapeHit outside = intersect_box({{5, 0.2f, 0.3f}, {-1, 0, 0}}, kInfinity);
    EXPECT_NEAR(outside.t, 4.0f, kT);
    EXPECT_EQ(outside.part, 1u); // +x face
    const ShapeHit inside = intersect_box({{0, 0, 0}, {0, 0, -1}}, kInfinity);
    EXPECT_NEAR(inside.t, 1.0f, kT);
    EXPECT_EQ(inside.part, 4u); // −z face
    EXPECT_FALSE(intersect_box({{5, 1.5f, 0}, {-1, 0, 0}}, kInfinity).found());
    // Parallel to a face, on its plane's outside: miss; just inside: hit.
    EXPECT_FALSE(intersect_box({{5, 1.0001f, 0}, {-1, 0, 0}}, kInfinity).found());
    EXPECT_TRUE(intersect_box({{5, 0.9999f, 0}, {-1, 0, 0}}, kInfinity).found());
}

TEST(Cylinder, HitsTheSideAndBothCaps) {
    const ShapeHit side = intersect_cylinder({{5, 0.5f, 0}, {-1, 0, 0}}, kInfinity);
    EXPECT_NEAR(side.t, 4.0f, kT);
    EXPECT_EQ(side.part, 0u);
    const ShapeHit top = intersect_cylinder({{0.2f, 5, 0}, {0, -1, 0}}, kInfinity);
    EXPECT_NEAR(top.t, 4.0f, kT);
    EXPECT_EQ(top.part, 2u);
    const ShapeHit bottom = intersect_cylinder({{0.2f, -3, 0}, {0, 1, 0}}, kInfinity);
    EXPECT_NEAR(bottom.t, 3.0f, kT);
    EXPECT_EQ(bottom.part, 1u);
    EXPECT_FALSE(intersect_cylinder({{5, 1.5f, 0}, {-1, 0, 0}}, kInfinity).found());
    // Inside, looking out through the side.
    EXPECT_NEAR(intersect_cylinder({{0, 0.5f, 0}, {0, 0, 1}}, kInfinity).t, 1.0f, kT);
}

TEST(Cylinder, OpenHasNoCapsSoRaysThroughTheEndsSeeTheInsideWall) {
    // Down the axis: through both open ends, nothing.
    EXPECT_FALSE(intersect_cylinder({{0.2f, 5, 0}, {0, -1, 0}}, kInfinity, true).found());
    // Slanting in through the top opening: the far wall from inside (x = −1 at y = 0.5).
    const ShapeHit inner = intersect_cylinder({{0, 1.5f, 0}, {-1, -1, 0}}, kInfinity, true);
    EXPECT_NEAR(inner.t, 1.0f, kT);
    EXPECT_EQ(inner.part, 0u);
    // The side is unchanged.
    EXPECT_NEAR(intersect_cylinder({{5, 0.5f, 0}, {-1, 0, 0}}, kInfinity, true).t, 4.0f, kT);
}

TEST(Cone, OpenTruncatedConeHasOnlyItsSlantedSide) {
    // Radius 1 at y = 0 to 0.5 at y = 1; along the axis the capped one is hit at the base.
    EXPECT_TRUE(intersect_cone({{0, -2, 0}, {0, 1, 0}}, 0.5f, kInfinity).found());
    EXPECT_FALSE(intersect_cone({{0, -2, 0}, {0, 1, 0}}, 0.5f, kInfinity, true).found());
    EXPECT_NEAR(intersect_cone({{5, 0.5f, 0}, {-1, 0, 0}}, 0.5f, kInfinity, true).t, 4.25f, kT);
}

TEST(Cone, RadiusShrinksLinearlyToTheTopRadius) {
    // r(y) = 1 − y·(1 − top): at y = 0.5, r = 0.5 (top 0) or 0.75 (top 0.5).
    EXPECT_NEAR(intersect_cone({{5, 0.5f, 0}, {-1, 0, 0}}, 0.0f, kInfinity).t, 4.5f, kT);
    EXPECT_NEAR(intersect_cone({{5, 0.5f, 0}, {-1, 0, 0}}, 0.5f, kInfinity).t, 4.25f, kT);
    const ShapeHit base = intersect_cone({{0.5f, -2, 0}, {0, 1, 0}}, 0.0f, kInfinity);
    EXPECT_NEAR(base.t, 2.0f, kT);
    EXPECT_EQ(base.part, 1u);
    // A top cap exists only when top_radius > 0.
    const ShapeHit top = intersect_cone({{0.1f, 3, 0}, {0, -1, 0}}, 0.5f, kInfinity);
    EXPECT_NEAR(top.t, 2.0f, kT);
    EXPECT_EQ(top.part, 2u);
    const ShapeHit pointed = intersect_cone({{0.1f, 3, 0}, {0, -1, 0}}, 0.0f, kInfinity);
    EXPECT_NEAR(pointed.t, 3.0f - 0.9f, kT); // side at r(y) = 0.1 ⇒ y = 0.9
    EXPECT_EQ(pointed.part, 0u);
    EXPECT_FALSE(intersect_cone({{5, 0.5f, 0.6f}, {-1, 0, 0}}, 0.0f, kInfinity).found());
}

TEST(Triangle, ReturnsDistanceAndBarycentrics) {
    const TriangleHit h =
        intersect_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {{0.25f, 0.5f, 2}, {0, 0, -1}});
    EXPECT_NEAR(h.t, 2.0f, kT);
    EXPECT_NEAR(h.u, 0.25f, kT);
    EXPECT_NEAR(h.v, 0.5f, kT);
    EXPECT_EQ(intersect_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {{0.6f, 0.6f, 2}, {0, 0, -1}}).t,
              kInfinity);
}

TEST(Mesh, ReturnsTheNearestTriangle) {
    const Scene scene = scene_at_origin(R"([{"shape": "mesh",
        "vertices": [[-1, -1, -3], [1, -1, -3], [0, 1, -3], [-1, -1, -5], [1, -1, -5], [0, 1, -5]],
        "indices": [3, 4, 5, 0, 1, 2]}])");
    const World world(scene);
    const Hit h = cast(world, Vec3(0.0f), {0, 0, -1});
    EXPECT_NEAR(h.t, 3.0f, kT);
    EXPECT_EQ(h.primitive, 1u);
}

// World-space answers for transformed objects (camera at the origin, so world = scene space).
TEST(TransformedShapes, TranslatedAndNonUniformlyScaledSphere) {
    const World world(scene_at_origin(R"([{"shape": "sphere", "transform": [
        {"scale": [2, 1, 1]}, {"translate": [10, 0, 0]}]}])"));
    EXPECT_NEAR(cast(world, Vec3(0.0f), {1, 0, 0}).t, 8.0f, 8 * kT);
    // Along y through x = 11: the ellipse (x−10)²/4 + y² = 1 gives y = ±√(3/4).
    const Hit h = cast(world, {11, -5, 0}, {0, 1, 0});
    EXPECT_NEAR(h.t, 5.0f - std::sqrt(0.75f), 5 * kT);
    const SurfacePoint s = world.surface({{11, -5, 0}, {0, 1, 0}}, h);
    // Normal of the ellipsoid: ∇((x−10)²/4 + y²) = ((x−10)/2, 2y) at (11, −√0.75).
    const Vec3 expected = glm::normalize(Vec3(0.5f, -2 * std::sqrt(0.75f), 0));
    EXPECT_NEAR(glm::distance(s.normal, expected), 0, 1e-5);
}

TEST(TransformedShapes, RotatedBoxIsHitOnItsEdge) {
    // Rotated 45° about y, the box's vertical edge points at −x, at distance √2 from the centre.
    const World world(scene_at_origin(R"([{"shape": "box", "transform": [
        {"rotate": {"axis": [0, 1, 0], "degrees": 45}}, {"translate": [0, 0, -3]}]}])"));
    EXPECT_NEAR(cast(world, {-5, 0, -3}, {1, 0, 0}).t, 5.0f - std::sqrt(2.0f), 5 * kT);
}

TEST(TransformedShapes, ShearedSphere) {
    // M maps (x, y, z) to (x + y, y, z); M⁻¹ takes the ray from (0.5, 5, 0) along −y to
    // (−4.5 + t, 5 − t, 0) in object space: 2t² − 19t + 44.25 = 0, t = (19 − √7)/4.
    const World world(scene_at_origin(R"([{"shape": "sphere", "transform": [{"matrix":
        [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]}])"));
    EXPECT_NEAR(cast(world, {0.5f, 5, 0}, {0, -1, 0}).t, (19.0f - std::sqrt(7.0f)) / 4, 5 * kT);
}

TEST(TransformedShapes, ScaledAndRotatedCylinderConeDiskAndTriangle) {
    // A cylinder of radius 0.5 and height 3 lying along x (rotated −90° about z: y → x).
    const World cylinder(
        scene_at_origin(R"([{"shape": "cylinder", "transform": [{"scale": [0.5, 3, 0.5]},
        {"rotate": {"axis": [0, 0, 1], "degrees": -90}}, {"translate": [0, 0, -4]}]}])"));
    EXPECT_NEAR(cast(cylinder, Vec3(1, 0, 0), {0, 0, -1}).t, 3.5f, 4 * kT);
    EXPECT_NEAR(cast(cylinder, Vec3(-2, 0, -4), {1, 0, 0}).t, 2.0f, 4 * kT); // base cap at x = 0
    // A cone twice as tall (height 2), radius 1 at its base: at height 1 its radius is 0.5.
    const World cone(scene_at_origin(R"([{"shape": "cone", "transform": [{"scale": [1, 2, 1]},
        {"translate": [0, -1, -4]}]}])"));
    EXPECT_NEAR(cast(cone, Vec3(0, 0, 0), {0, 0, -1}).t, 3.5f, 4 * kT);
    // A disk of radii 2 (x) and 1 (z) standing upright facing +z (rotated 90° about x).
    const World disk(scene_at_origin(R"([{"shape": "disk", "transform": [{"scale": [2, 1, 1]},
        {"rotate": {"axis": [1, 0, 0], "degrees": 90}}, {"translate": [0, 0, -4]}]}])"));
    EXPECT_NEAR(cast(disk, Vec3(1.9f, 0, 0), {0, 0, -1}).t, 4.0f, 4 * kT);
    EXPECT_FALSE(cast(disk, Vec3(0, 1.1f, 0), {0, 0, -1}).found());
    // A triangle scaled ×3 in x: (0.9, 0.1) lies inside (3·0.3 along the base).
    const World triangle(
        scene_at_origin(R"([{"shape": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
        "transform": [{"scale": [3, 1, 1]}, {"translate": [0, 0, -2]}]}])"));
    EXPECT_NEAR(cast(triangle, Vec3(0.9f, 0.1f, 0), {0, 0, -1}).t, 2.0f, 2 * kT);
    EXPECT_FALSE(cast(triangle, Vec3(2.9f, 0.1f, 0), {0, 0, -1}).found());
}

TEST(TransformedShapes, ClosestOfSeveralObjectsWinsAndTiesGoToTheLowerIndex) {
    const World world(scene_at_origin(R"([
        {"shape": "sphere", "transform": [{"translate": [0, 0, -10]}]},
        {"shape": "sphere", "transform": [{"translate": [0, 0, -5]}]},
        {"shape": "sphere", "transform": [{"translate": [0, 0, -5]}]}])"));
    const Hit h = cast(world, Vec3(0.0f), {0, 0, -1});
    EXPECT_EQ(h.object, 1u);
    EXPECT_NEAR(h.t, 4.0f, kT);
}

// What each shape's traits (trace/shapes/table.h) claim, held to its geometry through the
// World's dispatch: every hit lies in the shape's bounds, and where the spawn rule trusts
// convexity or planarity (SurfacePoint::skip), no ray leaving on the normal's side meets the
// shape again. The leaving rays start 1e-4 off the surface, far above float's rounding at these
// sizes, so a hit would be another part of the shape, not the same point found again.
class ShapeTraitsTest : public ::testing::TestWithParam<const char*> {};

TEST_P(ShapeTraitsTest, HitsLieInTheBoundsAndSkippedShapesCannotBeMetAgain) {
    const World world(scene_at_origin(std::string("[") + GetParam() + "]"));
    const Object& object = world.objects()[0];
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    const auto random_unit = [&] {
        for (;;) {
            const Vec3 v(u(rng), u(rng), u(rng));
            if (glm::dot(v, v) > 1e-2f && glm::dot(v, v) <= 1) return glm::normalize(v);
        }
    };
    int hits = 0, skips = 0;
    for (int k = 0; k < 400; ++k) {
        const Vec3 origin = 4.0f * random_unit();
        const Ray ray{origin, Vec3(u(rng), u(rng), u(rng)) - origin};
        const Hit hit = world.intersect(ray);
        if (!hit.found()) continue;
        ++hits;
        const SurfacePoint s = world.surface(ray, hit);
        if (object.bounded) {
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(s.position, object.bounds.lo - 1e-5f)));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(s.position, object.bounds.hi + 1e-5f)));
        }
        if (s.skip != hit.object) continue;
        ++skips;
        for (int j = 0; j < 8; ++j) {
            Vec3 d = random_unit();
            if (glm::dot(d, s.normal) < 0) d = -d;
            const Hit again = world.intersect_one(0, {s.position + 1e-4f * s.normal, d});
            EXPECT_FALSE(again.found())
                << "left " << s.position.x << ", " << s.position.y << ", " << s.position.z
                << " along " << d.x << ", " << d.y << ", " << d.z << ", met again at t " << again.t;
        }
    }
    EXPECT_GT(hits, 50);
    const ShapeTraits& traits = shape_traits(object.shape);
    if (traits.planar || traits.convex) {
        EXPECT_GT(skips, 0); // the claim was put to the test
    } else {
        EXPECT_EQ(skips, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(
    EveryShape, ShapeTraitsTest,
    ::testing::Values(
        R"({"shape": "sphere"})", R"({"shape": "plane"})", R"({"shape": "box"})",
        R"({"shape": "disk"})", R"({"shape": "cylinder"})",
        R"({"shape": "cylinder", "open": true})", R"({"shape": "cone", "top_radius": 0.5})",
        R"({"shape": "cone", "top_radius": 2})", R"({"shape": "cone"})",
        R"({"shape": "cone", "top_radius": 0.5, "open": true})",
        R"({"shape": "triangle", "vertices": [[-1, -1, 0], [1, -1, 0], [0, 1, 0.5]]})",
        // Two facing quads: not convex, and a ray leaving one can meet the other.
        R"({"shape": "mesh", "vertices": [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
            [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]],
            "indices": [0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6]})"),
    [](const ::testing::TestParamInfo<const char*>& info) {
        return "shape_" + std::to_string(info.index);
    });

} // namespace
} // namespace glint
