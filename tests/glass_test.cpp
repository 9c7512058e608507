// Transmission, shadows through transmissive surfaces and the checker, exactly per
// docs/ARCHITECTURE.md's conventions: Snell's law at several angles both ways, total internal
// reflection just past the critical angle, a slab that displaces a ray without bending it,
// hand-computed shadow and checker pixels, and a ray tree's counts by kind.
#include "test_scenes.h"

#include "trace/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit direction at `degrees` from −n in the xy plane, n = +y.
Vec3 incoming(double degrees) {
    const double a = degrees * kPi / 180;
    return Vec3(static_cast<float>(std::sin(a)), static_cast<float>(-std::cos(a)), 0.0f);
}

TEST(Refract, SnellsLawHoldsAtSeveralAnglesEnteringAndExiting) {
    const Vec3 n(0, 1, 0);
    for (const double ior : {1.1, 1.5, 2.4}) {
        for (const double degrees : {0.0, 10.0, 30.0, 60.0, 85.0}) {
            for (const double eta : {1 / ior, ior}) { // entering, exiting
                const double sin_in = std::sin(degrees * kPi / 180);
                if (eta * sin_in >= 1) continue; // past the critical angle: the next test
                bool total = true;
                const Vec3 t = refract(incoming(degrees), n, static_cast<float>(eta), total);
                EXPECT_FALSE(total);
                EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f) << "unit in, unit out";
                EXPECT_LT(t.y, 0.0f) << "goes on through the surface";
                EXPECT_NEAR(t.x, eta * sin_in, 1e-6) << "sin θt = η sin θi at " << degrees;
                EXPECT_EQ(t.z, 0.0f) << "stays in the plane of incidence";
            }
        }
    }
}

TEST(Refract, TotalInternalReflectionStartsJustPastTheCriticalAngle) {
    const Vec3 n(0, 1, 0);
    const double critical = std::asin(1 / 1.5) * 180 / kPi; // 41.81°
    bool total = false;
    refract(incoming(critical - 0.05), n, 1.5f, total);
    EXPECT_FALSE(total);
    const Vec3 d = incoming(critical + 0.05);
    const Vec3 t = refract(d, n, 1.5f, total);
    EXPECT_TRUE(total);
    EXPECT_EQ(t, reflect(d, n));
}

// A ray through a glass slab 0.4 thick at 40° leaves parallel to itself, shifted sideways by
// thickness · sin(θ − θt) / cos θt, and the World finds both walls (the spawn rule for rays
// into a solid: they step off the entry face and must still meet the far one).
TEST(Glass, ASlabDisplacesARayWithoutBendingIt) {
    const World world(testing::scene_at_origin(
        R"([{"shape": "box", "material": "glass", "transform": [{"scale": [5, 0.2, 5]}]}])",
        R"({"glass": {"transmission": 1, "ior": 1.5}})"));
    const Vec3 d = incoming(40);
    Ray ray{Vec3(0, 0.2f, 0) + (1.8f / d.y) * d, d}; // from y = 2, meets the top face at x = 0
    const Vec3 start = ray.origin;
    for (int wall = 0; wall < 2; ++wall) {
        const Hit hit = world.intersect(ray);
        ASSERT_TRUE(hit.found()) << "wall " << wall;
        const SurfacePoint s = world.surface(ray, hit);
        EXPECT_EQ(s.entering, wall == 0);
        bool total = true;
        const Vec3 t =
            refract(glm::normalize(ray.direction), s.normal, s.entering ? 1 / 1.5f : 1.5f, total);
        ASSERT_FALSE(total);
        ray = {s.spawn_through(), t};
    }
    EXPECT_NEAR(ray.direction.x, d.x, 1e-6f);
    EXPECT_NEAR(ray.direction.y, d.y, 1e-6f);
    const double inside = std::asin(std::sin(40 * kPi / 180) / 1.5);
    const double shift = 0.4 * std::sin(40 * kPi / 180 - inside) / std::cos(inside);
    // Distance of the exit point from the line the ray came in on.
    const Vec3 offset = ray.origin - start;
    const Vec3 across = offset - glm::dot(offset, d) * d;
    EXPECT_NEAR(glm::length(across), shift, 1e-5);
}

// A floor point straight below a light, seen by a 1×1 camera from the side; the light passes
// through boxes of glass, each crossed twice: colour = light · diffuse · Π transmissions.
RenderResult floor_under(const std::string& boxes) {
    return render(World(parse_scene(R"({
        "camera": {"eye": [3, 1, 0], "look_at": [0, 0, 0], "width": 1, "height": 1},
        "lights": [{"position": [0, 10, 0]}],
        "materials": {"floor": {"ambient": [0, 0, 0], "diffuse": [0.8, 0.8, 0.8]},
                      "half": {"transmission": 0.5}, "most": {"transmission": 0.8},
                      "opaque": {}},
        "objects": [{"shape": "plane", "material": "floor"})" +
                                        boxes + "]}",
                                    "floor.json")));
}

std::string box_at(const char* material, double y) {
    return R"(, {"shape": "box", "material": ")" + std::string(material) +
           R"(", "transform": [{"scale": 0.5}, {"translate": [0, )" + std::to_string(y) + ", 0]}]}";
}

TEST(Glass, ShadowsPassThroughOneAndTwoTransmissiveObjects) {
    const RenderResult open = floor_under("");
    EXPECT_EQ(open.bytes().rgb[0], std::lround(255 * 0.8));
    EXPECT_EQ(open.rays.shadow, 1u);
    const RenderResult one = floor_under(box_at("half", 4));
    EXPECT_EQ(one.bytes().rgb[0], std::lround(255 * 0.8 * 0.5 * 0.5));
    EXPECT_EQ(one.rays.shadow, 3u) << "to the box, through it, on to the light";
    const RenderResult two = floor_under(box_at("half", 4) + box_at("most", 6));
    EXPECT_EQ(two.bytes().rgb[0], std::lround(255 * 0.8 * 0.25 * 0.64));
    EXPECT_EQ(two.rays.shadow, 5u);
    const RenderResult blocked = floor_under(box_at("half", 4) + box_at("opaque", 6));
    EXPECT_EQ(blocked.bytes().rgb[0], 0);
}

// A 2×2 view straight down on a checkered plane at the origin: the pixel centres land at
// (±a, 0, ±a), a < 1, in cells k = ⌊x⌋ + ⌊z⌋: 0 and −2 (even, the material's red) on the
// diagonal, −1 (odd in the floor sense, the checker's green) off it.
TEST(Checker, CellsFollowTheFloorParityInObjectSpace) {
    for (const char* transform : {"[]", R"([{"translate": [0, -2, 0]}])"}) {
        const Scene scene = parse_scene(std::string(R"({
            "camera": {"eye": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov_y": 30,
                       "width": 2, "height": 2},
            "ambient": [1, 1, 1],
            "materials": {"c": {"ambient": [1, 0, 0], "diffuse": [0, 0, 0],
                                "checker": {"size": 1, "diffuse": [0, 0, 0], "ambient": [0, 1, 0]}}},
            "objects": [{"shape": "plane", "material": "c", "transform": )") +
                                            transform + "}]}",
                                        "checker.json");
        const Image image = render(World(scene)).bytes();
        const auto green = [&](int x, int y) { return image.pixel(x, y)[1] == 255; };
        EXPECT_FALSE(green(0, 0)) << transform;
        EXPECT_TRUE(green(1, 0)) << transform;
        EXPECT_TRUE(green(0, 1)) << transform;
        EXPECT_FALSE(green(1, 1)) << transform;
    }
}

// One glass sphere (reflectivity 0.5, transmission 1, no local terms) on the axis of a 1×1
// camera, max_depth 2, nothing else in view. The tree: at the front (depth 0) a reflection
// (background) and a transmission to the back wall; there (depth 1) a reflection back to the
// front wall and a transmission out (background); at the front wall again (depth 2) both rays
// are cut, weights 0.5·0.5 and 0.5·1. Colour = 0.5·B + 1·(0.5·0 + 1·B) = 1.5·B.
TEST(Glass, ARayTreeCastsAndCutsTheHandCountedRays) {
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 1, "height": 1},
        "background": [0.1, 0.1, 0.1],
        "materials": {"g": {"ambient": [0, 0, 0], "diffuse": [0, 0, 0], "reflectivity": 0.5,
                            "transmission": 1}},
        "render": {"max_depth": 2, "min_weight": 0},
        "objects": [{"shape": "sphere", "material": "g"}]})",
                                    "tree.json");
    const RenderResult r = render(World(scene));
    EXPECT_EQ(r.rays.primary, 1u);
    EXPECT_EQ(r.rays.reflection, 2u);
    EXPECT_EQ(r.rays.transmission, 2u);
    EXPECT_EQ(r.rays.shadow, 0u);
    EXPECT_FLOAT_EQ(r.omitted_weight[0], 0.75f);
    EXPECT_EQ(r.bytes().rgb[0], std::lround(255 * 0.15));
}

// A glass sphere and the camera inside a closed mirror box, as deep as glint allows and with no
// weight cut-off: no ray escapes, and every glass hit casts two, so the tree would double at
// each of 64 levels. The pixel's budget stops it, and what it stops is counted as omitted.
TEST(Glass, APixelsRayTreeStaysWithinItsBudget) {
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0], "width": 6, "height": 4},
        "materials": {"g": {"reflectivity": 0.5, "transmission": 0.5, "ior": 1.5},
                      "m": {"reflectivity": 1}},
        "render": {"max_depth": 64, "min_weight": 0},
        "objects": [{"shape": "sphere", "material": "g"},
                    {"shape": "box", "material": "m", "transform": [{"scale": 5}]}]})",
                                    "budget.json");
    const RenderResult r = render(World(scene));
    const std::uint64_t pixels = r.omitted_weight.size();
    EXPECT_LE(r.rays.reflection + r.rays.transmission, pixels * kMaxTreeRays);
    EXPECT_GT(r.rays.reflection + r.rays.transmission, pixels * kMaxTreeRays / 2)
        << "most pixels should reach the budget";
    EXPECT_GT(*std::max_element(r.omitted_weight.begin(), r.omitted_weight.end()), 0.0f);
}

// Every structure and both primary modes give the same bytes on a glass scene.
TEST(Glass, EveryStructureRendersTheSameBytes) {
    const Scene scene = testing::shipped("whitted", 96, 72);
    const Image list = render(World(scene, AccelKind::list)).bytes();
    for (const AccelKind kind : all_values<AccelKind>())
        EXPECT_EQ(render(World(scene, kind)).bytes().rgb, list.rgb) << name_of(kind);
}

} // namespace
} // namespace glint
