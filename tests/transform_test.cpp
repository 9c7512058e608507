// Transforms: composition order, classification, round trips, rejection of unusable matrices,
// and transformed normals checked against finite differences of the hit surface.
#include "test_scenes.h"

#include "trace/transform.h"

#include <gtest/gtest.h>

#include <random>

namespace glint {
namespace {

using testing::scene_at_origin;

DVec3 apply(const DMat4& m, DVec3 p) {
    return DVec3(m * glm::dvec4(p, 1.0));
}

TEST(Transform, ListEntriesApplyInOrderFirstEntryFirst) {
    // [scale 2, rotate z 90°, translate x 1]: (1,0,0) → (2,0,0) → (0,2,0) → (1,2,0).
    const Scene scene = scene_at_origin(R"([{"shape": "sphere", "transform": [
        {"scale": 2}, {"rotate": {"axis": [0, 0, 1], "degrees": 90}}, {"translate": [1, 0, 0]}]}])");
    const DVec3 p = apply(scene.objects[0].transform, {1, 0, 0});
    EXPECT_NEAR(p.x, 1, 1e-12);
    EXPECT_NEAR(p.y, 2, 1e-12);
    EXPECT_NEAR(p.z, 0, 1e-12);
}

TEST(Transform, MatrixIsRowMajorActingOnColumnVectors) {
    const Scene scene = scene_at_origin(R"([{"shape": "sphere", "transform": [{"matrix":
        [[1, 2, 0, 5], [0, 1, 0, 6], [0, 0, 3, 7], [0, 0, 0, 1]]}]}])");
    const DVec3 p = apply(scene.objects[0].transform, {1, 1, 1});
    EXPECT_EQ(p, DVec3(1 + 2 + 5, 1 + 6, 3 + 7));
}

TEST(Transform, ClassifiesByWhatTheStoredMatrixDoes) {
    EXPECT_EQ(make_transform(DMat4(1.0)).kind, TransformClass::identity);
    EXPECT_EQ(make_transform(translation_matrix({1, 2, 3})).kind, TransformClass::translation);
    EXPECT_EQ(make_transform(translation_matrix({1, 2, 3}) * scale_matrix(DVec3(2.5))).kind,
              TransformClass::uniform_scale);
    EXPECT_EQ(make_transform(scale_matrix({-2, -2, -2})).kind, TransformClass::general); // mirror
    EXPECT_EQ(make_transform(scale_matrix({1, 2, 1})).kind, TransformClass::general);
    EXPECT_EQ(make_transform(rotation_matrix({0, 1, 0}, 30)).kind, TransformClass::general);
}

TEST(Transform, FastPathsAgreeWithTheGeneralMatrix) {
    for (const DMat4& m : {DMat4(1.0), translation_matrix({1e3, -2, 0.5}),
                           translation_matrix({4, 5, 6}) * scale_matrix(DVec3(0.25))}) {
        Transform fast = make_transform(m);
        Transform general = fast;
        general.kind = TransformClass::general;
        const Ray ray{{0.3f, -1.7f, 2.0f}, {0.2f, 0.5f, -1.0f}};
        const Ray a = fast.to_object(ray), b = general.to_object(ray);
        for (int i = 0; i < 3; ++i) {
            EXPECT_FLOAT_EQ(a.origin[i], b.origin[i]);
            EXPECT_FLOAT_EQ(a.direction[i], b.direction[i]);
        }
        const Vec3 n = glm::normalize(Vec3(1, 2, 3));
        EXPECT_NEAR(glm::distance(fast.normal_to_world(n), general.normal_to_world(n)), 0, 1e-6);
        EXPECT_NEAR(fast.normal_stretch(n), general.normal_stretch(n), 1e-6);
        // The spawn offset's bound: for a translation or a uniform scale scalar products, the
        // same bits as the matrix's (whose zeros add nothing to a finite vector). An identity's
        // is its own, tighter.
        if (fast.kind == TransformClass::identity) continue;
        for (const Vec3 p : {Vec3(0.3f, -1.7f, 2.0f), Vec3(-1e4f, 3e-5f, 0.0f), Vec3(1e-30f)}) {
            const Vec3 a_error = fast.roundtrip_error(p, Vec3(1e-7f));
            const Vec3 b_error = general.roundtrip_error(p, Vec3(1e-7f));
            for (int i = 0; i < 3; ++i) EXPECT_EQ(a_error[i], b_error[i]) << "axis " << i;
        }
    }
}

TEST(Transform, ObjectAndWorldRoundTripWithinTheStatedBound) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const DMat4 m = translation_matrix({u(rng) * 100, u(rng) * 100, u(rng) * 100}) *
                        rotation_matrix({u(rng), u(rng), 1}, u(rng) * 180) *
                        scale_matrix({1.5 + u(rng), 0.01 + std::abs(u(rng)), 3 + u(rng)});
        const Transform t = make_transform(m);
        const Vec3 p(static_cast<float>(u(rng)), static_cast<float>(u(rng)),
                     static_cast<float>(u(rng)));
        const Vec3 back = t.to_object({t.point_to_world(p), Vec3(0.0f)}).origin;
        const Vec3 bound = t.roundtrip_error(p, Vec3(0.0f));
        for (int i = 0; i < 3; ++i)
            EXPECT_LE(std::abs(back[i] - p[i]), bound[i]) << "trial " << trial;
    }
}

TEST(Transform, RejectsSingularAndIllConditionedMatrices) {
    EXPECT_TRUE(why_unusable(scale_matrix({1, 0, 1})).has_value());
    DMat4 shear(1.0);
    shear[1][0] = 1;        // x += y
    shear[0][1] = 1 - 1e-7; // y += (1 − 1e-7)·x: rows nearly parallel
    const auto why = why_unusable(shear);
    ASSERT_TRUE(why.has_value());
    EXPECT_NE(why->find("condition number"), std::string::npos) << *why;
    DMat4 projective(1.0);
    projective[0][3] = 0.5;
    EXPECT_TRUE(why_unusable(projective).has_value());
}

TEST(Transform, AcceptsRotatedScalesUpTo1e4Each) {
    // Row scaling makes any rotated non-uniform scale perfectly conditioned for float.
    const DMat4 m = rotation_matrix({1, 2, 3}, 40) * scale_matrix({1e-4, 1e4, 1});
    EXPECT_FALSE(why_unusable(m).has_value());
}

// The surface near a hit, from rays a little to either side of it: its tangents must be
// perpendicular to the normal glint reports there.
class NormalTest : public ::testing::TestWithParam<const char*> {};

TEST_P(NormalTest, NormalsArePerpendicularToFiniteDifferenceTangents) {
    const std::string shape = GetParam();
    const std::string extra = shape == "cone" ? R"(, "top_radius": 0.3)"
                              : shape == "triangle"
                                  ? R"(, "vertices": [[-1, -1, 0.2], [1, -1, 0], [0, 1, -0.3]])"
                                  : "";
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    int checked = 0;
    for (int trial = 0; trial < 80; ++trial) {
        // Random general affine maps, shear included, placed 6 units in front of the camera.
        const std::string matrix =
            "[[" + std::to_string(1 + 0.5 * u(rng)) + ", " + std::to_string(0.6 * u(rng)) + ", " +
            std::to_string(0.4 * u(rng)) + ", 0], [" + std::to_string(0.5 * u(rng)) + ", " +
            std::to_string(0.8 + 0.3 * u(rng)) + ", " + std::to_string(0.3 * u(rng)) + ", 0], [" +
            std::to_string(0.2 * u(rng)) + ", " + std::to_string(0.4 * u(rng)) + ", " +
            std::to_string(1.2 + 0.3 * u(rng)) + ", -6], [0, 0, 0, 1]]";
        const Scene scene = testing::scene_at_origin(
            R"([{"shape": ")" + shape +
            R"(", "transform": [{"rotate": {"axis": [1, 1, 0], "degrees": )" +
            std::to_string(90 * u(rng)) + R"(}}, {"matrix": )" + matrix + "}]" + extra + "}]");
        const World world(scene);
        const Vec3 d = glm::normalize(Vec3(0.15 * u(rng), 0.15 * u(rng), -1.0));
        const Hit hit = testing::cast(world, Vec3(0.0f), d);
        if (!hit.found()) continue;
        const SurfacePoint s = world.surface({Vec3(0.0f), d}, hit);
        // Near grazing incidence the two neighbours land at very different distances from the
        // hit, and the chord tilts by O(h·curvature): keep to rays at least ~17° off the surface.
        if (std::abs(glm::dot(s.normal, d)) < 0.3f) continue;
        const float h = 1e-3f;
        const Vec3 side1 = glm::normalize(glm::cross(d, Vec3(0, 1, 0)));
        const Vec3 side2 = glm::normalize(glm::cross(d, side1));
        for (Vec3 side : {side1, side2}) {
            // Central differences: the chord through p(−h) and p(+h) is parallel to the tangent
            // plane up to O(h²·curvature), far below the tolerance.
            const Vec3 d_plus = glm::normalize(d + h * side),
                       d_minus = glm::normalize(d - h * side);
            const Hit plus = testing::cast(world, Vec3(0.0f), d_plus);
            const Hit minus = testing::cast(world, Vec3(0.0f), d_minus);
            // Only where both neighbours land on the same smooth part (not across an edge).
            if (!plus.found() || !minus.found() || plus.object != hit.object ||
                minus.object != hit.object || plus.primitive != hit.primitive ||
                minus.primitive != hit.primitive)
                continue;
            const Vec3 tangent = glm::normalize(plus.t * d_plus - minus.t * d_minus);
            // 2e-3: float hit points (relative error ~1e-6 at t ≈ 6) over a chord of ~1e-2.
            EXPECT_LT(std::abs(glm::dot(tangent, s.normal)), 2e-3f) << shape << " trial " << trial;
            ++checked;
        }
        EXPECT_LT(glm::dot(s.normal, d), 0.0f) << "normal faces the incoming ray";
    }
    EXPECT_GT(checked, 20) << "too few hits to say anything about " << shape;
}

INSTANTIATE_TEST_SUITE_P(EveryShape, NormalTest,
                         ::testing::Values("sphere", "plane", "box", "disk", "cylinder", "cone",
                                           "triangle"),
                         [](const auto& info) { return std::string(info.param); });

} // namespace
} // namespace glint
