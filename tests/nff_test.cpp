// NFF import: each entity mapped to glint's scene, polygons triangulated, and every malformed
// input reported with its file and line.
#include "test_scenes.h"

#include "io/load_scene.h"
#include "io/nff_loader.h"
#include "io/polygon.h"
#include "trace/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

namespace glint {
namespace {

const std::string kView = "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\n"
                          "resolution 64 48\n";

Scene nff(const std::string& body) {
    return parse_nff(kView + body, "t.nff");
}

DVec3 apply(const DMat4& m, DVec3 p) {
    return DVec3(m * glm::dvec4(p, 1.0));
}

TEST(Nff, ViewMapsToTheCameraWithTheAngleBetweenOuterPixelCentres) {
    const Scene s = nff("");
    EXPECT_EQ(s.camera.eye, DVec3(0, 0, 10));
    EXPECT_EQ(s.camera.look_at, DVec3(0, 0, 0));
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.camera.height, 48);
    // The outermost row's centre lies half a pixel inside the image edge: at (1 − 1/48)·tan(fov/2).
    const double edge = std::tan(s.camera.fov_y * std::numbers::pi / 360);
    EXPECT_NEAR(edge * (1 - 1.0 / 48), std::tan(22.5 * std::numbers::pi / 180), 1e-12);
    // SPD's rules: 4 reflections (a ray tree 5 deep), no adaptive cut-off.
    EXPECT_EQ(s.render.max_depth, 4);
    EXPECT_EQ(s.render.min_reflectivity, 0.0f);
}

TEST(Nff, LightsWithoutColourShareAUnitTotalAndColouredOnesKeepTheirs) {
    const Scene s = nff("l 1 2 3\nl 4 5 6 0.5 0.25 1\nl 0 0 0\nl 1 1 1\n");
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[0].position, DVec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].color, glm::vec3(0.5f)); // 1/√4
    EXPECT_EQ(s.lights[1].color, glm::vec3(0.5f, 0.25f, 1.0f));
}

TEST(Nff, FillMapsKdKsAndShineAndUsesKsAsTheReflectivity) {
    const Scene s = nff("b 0.1 0.2 0.3\nf 1 0.5 0 0.8 0.3 20 0 1\ns 0 0 0 1\n");
    EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.3f));
    const Material& m = s.materials[s.objects.at(0).material];
    EXPECT_EQ(m.diffuse, glm::vec3(0.8f, 0.4f, 0.0f));
    EXPECT_EQ(m.specular, glm::vec3(0.3f));
    EXPECT_EQ(m.shininess, 20.0f);
    EXPECT_EQ(m.reflectivity, 0.3f);
    EXPECT_TRUE(s.notes.empty());
}

TEST(Nff, FillLinesGiveTransmissionAndTheIndexOfRefraction) {
    const Scene s =
        nff("f 1 1 1 0.5 0.5 3 0.8 1.25\ns 0 0 0 1\nf 1 1 1 0.5 0.5 3 0 0\ns 2 0 0 1\n");
    EXPECT_TRUE(s.notes.empty());
    const Material& glass = s.materials[s.objects[0].material];
    EXPECT_EQ(glass.transmission, 0.8f);
    EXPECT_EQ(glass.ior, 1.25f);
    // An opaque fill's index is not read (SPD writes 0 there) and leaves the default.
    const Material& opaque = s.materials[s.objects[1].material];
    EXPECT_EQ(opaque.transmission, 0.0f);
    EXPECT_EQ(opaque.ior, 1.5f);
}

TEST(Nff, SphereIsTheUnitSphereScaledAndMoved) {
    const Scene s = nff("s 1 2 3 0.5\n");
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].shape, ShapeKind::sphere);
    EXPECT_EQ(apply(s.objects[0].transform, DVec3(1, 0, 0)), DVec3(1.5, 2, 3));
}

// A `c` maps y = 0 to the base and y = 1 to the apex, radius r0 across at the base and
// top_radius·r0 = r1 at the apex, on any axis.
TEST(Nff, ConeIsAnOpenTruncatedConeOnItsAxis) {
    const Scene s = nff("c 1 1 1 2 4 5 6 0.5\n");
    ASSERT_EQ(s.objects.size(), 1u);
    const SceneObject& o = s.objects[0];
    EXPECT_EQ(o.shape, ShapeKind::cone);
    EXPECT_TRUE(o.open);
    EXPECT_FLOAT_EQ(o.top_radius, 0.25f);
    const DVec3 base(1, 1, 1), apex(4, 5, 6), axis = glm::normalize(apex - base);
    const DVec3 b = apply(o.transform, DVec3(0, 0, 0)), a = apply(o.transform, DVec3(0, 1, 0));
    EXPECT_NEAR(glm::length(b - base), 0, 1e-12);
    EXPECT_NEAR(glm::length(a - apex), 0, 1e-12);
    for (const DVec3 rim : {DVec3(1, 0, 0), DVec3(0, 0, 1), DVec3(0.6, 0, 0.8)}) {
        const DVec3 p = apply(o.transform, rim) - base;
        EXPECT_NEAR(glm::length(p), 2, 1e-12);    // radius r0 at the base
        EXPECT_NEAR(glm::dot(p, axis), 0, 1e-12); // across the axis
        const DVec3 q = apply(o.transform, rim * 0.25 + DVec3(0, 1, 0)) - apex;
        EXPECT_NEAR(glm::length(q), 0.5, 1e-12); // r1 at the apex
    }
}

TEST(Nff, EqualRadiiMakeAnOpenCylinderAndAZeroBaseRadiusSwapsTheEnds) {
    const Scene s = nff("c 0 0 0 1 0 3 0 1\nc 0 0 0 0 0 2 0 1\n");
    ASSERT_EQ(s.objects.size(), 2u);
    EXPECT_EQ(s.objects[0].shape, ShapeKind::cylinder);
    EXPECT_TRUE(s.objects[0].open);
    EXPECT_EQ(s.objects[1].shape, ShapeKind::cone);
    EXPECT_EQ(s.objects[1].top_radius, 0.0f);
    EXPECT_NEAR(glm::length(apply(s.objects[1].transform, DVec3(0)) - DVec3(0, 2, 0)), 0, 1e-12);
}

TEST(Nff, EntriesAreTokensWhateverTheLineBreaks) {
    const Scene one_line = nff("c 1 1 1 2 4 5 6 0.5 p 3 0 0 0 1 0 0 0 1 0");
    const Scene spread = nff("c\n1 1 1 2\n4 5 6 0.5\np 3\n0 0 0\n1 0 0\n0 1 0\n");
    ASSERT_EQ(one_line.objects.size(), spread.objects.size());
    EXPECT_EQ(one_line.objects[0].transform, spread.objects[0].transform);
    EXPECT_EQ(one_line.meshes[0].vertices, spread.meshes[0].vertices);
}

TEST(Nff, PolygonsOfOneMaterialShareAMeshAndPatchesKeepTheirNormals) {
    const Scene s = nff("f 1 0 0 1 0 1 0 1\np 3 0 0 0 1 0 0 0 1 0\np 4 0 0 1 1 0 1 1 1 1 0 1 1\n"
                        "pp 3 0 0 2 0 0 2 1 0 2 1 0 0 0 1 2 0 0 3\n"
                        "f 0 1 0 1 0 1 0 1\np 3 0 0 0 1 0 0 0 1 0\n");
    // Red: one flat mesh (3 + 4 vertices, 1 + 2 triangles) and one smooth one; green: one flat.
    ASSERT_EQ(s.objects.size(), 3u);
    const TriangleMesh& flat = s.meshes[s.objects[0].mesh];
    EXPECT_EQ(flat.vertices.size(), 7u);
    EXPECT_EQ(flat.triangles.size(), 3u);
    EXPECT_TRUE(flat.normals.empty());
    const TriangleMesh& smooth = s.meshes[s.objects[1].mesh];
    ASSERT_EQ(smooth.normals.size(), 3u);
    EXPECT_EQ(smooth.normals[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(smooth.normals[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(smooth.normals[2], glm::vec3(0, 0, 1)); // normalised
    EXPECT_NE(s.objects[2].material, s.objects[0].material);
}

// Smooth shading: a ray hitting a patch between its vertices sees the interpolated normal.
TEST(Nff, PatchNormalsAreInterpolatedForShading) {
    const Scene s = nff("pp 3 -1 -1 0 -1 0 1  1 -1 0 1 0 1  0 1 0 0 0 1\n");
    const World world(s);
    const Ray ray = world.camera().ray(32, 24);
    const Hit hit = world.intersect(ray);
    ASSERT_TRUE(hit.found());
    const SurfacePoint p = world.surface(ray, hit);
    EXPECT_NEAR(p.normal.z, 1.0f, 1e-6f); // the facet faces the camera
    EXPECT_LT(p.shading.z, 0.999f);       // the shading normal leans as the vertices do
    EXPECT_NEAR(glm::length(p.shading), 1.0f, 1e-6f);
}

// Concave outlines: ear clipping covers exactly the polygon, with n − 2 triangles all wound as
// the polygon is.
TEST(Polygon, ConcaveGearOutlineIsCoveredExactly) {
    std::vector<glm::dvec3> gear;
    const int teeth = 36;
    for (int i = 0; i < teeth * 4; ++i) { // 144 vertices, as the SPD gears
        const double a = 2 * std::numbers::pi * i / (teeth * 4);
        const double r = (i / 2) % 2 == 0 ? 1.0 : 0.8;
        gear.push_back({r * std::cos(a), r * std::sin(a), 0.5});
    }
    const std::vector<glm::uvec3> triangles = triangulate_polygon(gear);
    ASSERT_EQ(triangles.size(), gear.size() - 2);
    double area = 0;
    for (const glm::uvec3& t : triangles) {
        const glm::dvec3 n = glm::cross(gear[t.y] - gear[t.x], gear[t.z] - gear[t.x]);
        EXPECT_GT(n.z, 0) << "every triangle wound as the polygon";
        area += n.z / 2;
    }
    EXPECT_NEAR(area, newell_normal(gear).z / 2, 1e-12);
}

TEST(Polygon, ClockwiseDuplicatesAndZeroArea) {
    // Clockwise seen from +z: triangles stay clockwise (facing −z).
    const std::vector<glm::dvec3> square{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    for (const glm::uvec3& t : triangulate_polygon(square))
        EXPECT_LT(glm::cross(square[t.y] - square[t.x], square[t.z] - square[t.x]).z, 0);
    // A repeated vertex and a collinear one: no zero-area triangle, the area covered once.
    const std::vector<glm::dvec3> messy{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 0}};
    double area = 0;
    for (const glm::uvec3& t : triangulate_polygon(messy)) {
        const double z = glm::cross(messy[t.y] - messy[t.x], messy[t.z] - messy[t.x]).z / 2;
        EXPECT_GT(z, 0);
        area += z;
    }
    EXPECT_DOUBLE_EQ(area, 2.0);
    EXPECT_TRUE(triangulate_polygon({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}).empty());
}

struct BadNff {
    const char* what;
    std::string text;
    const char* message; // expected in the error, after "t.nff:"
};

void PrintTo(const BadNff& bad, std::ostream* out) {
    *out << bad.what;
}

class NffErrorTest : public ::testing::TestWithParam<BadNff> {};

TEST_P(NffErrorTest, NamesTheFileAndLine) {
    try {
        parse_nff(GetParam().text, "t.nff");
        FAIL() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(std::string("t.nff:") + GetParam().message),
                  std::string::npos)
            << e.what();
    }
}

const std::string kV = "v from 0 0 1 at 0 0 0 up 0 1 0 angle 40 hither 1 resolution 8 8\n";

INSTANTIATE_TEST_SUITE_P(
    Bad, NffErrorTest,
    ::testing::Values(
        BadNff{"unknown entity", kV + "\nq 1 2 3\n", "3: unknown entity 'q'"},
        BadNff{"no view", "\ns 0 0 0 1\n", "1: no view"},
        BadNff{"bad number", kV + "s 0 0 zero 1\n",
               "2: expected a number for s's centre, got 'zero'"},
        BadNff{"truncated sphere", kV + "s 0 0\n\n", "2: the file ends inside 's' (line 2)"},
        BadNff{"infinite", kV + "s 0 0 0 inf\n", "2: expected a number"},
        BadNff{"huge", kV + "s 1e300 0 0 1\n", "2: s's centre is beyond 1e15"},
        BadNff{"zero radius", kV + "s 0 0 0 0\n", "2: the object's placement: transform is singular"},
        // The scene check's reach rule (io/scene_check.h), which NFF scenes now meet too.
        BadNff{"sphere reaching past 1e15", kV + "s 9e14 0 0 9e14\n",
               "2: the object's placement: the placed object reaches 1.8e+15 from the origin"},
        BadNff{"polygon of 2", kV + "p 2\n0 0 0\n1 1 1\n", "2: p's vertex count must be between 3"},
        BadNff{"fractional count", kV + "p 3.5\n", "2: p's vertex count must be a whole number"},
        BadNff{"short polygon", kV + "p 4\n0 0 0\n1 0 0\n1 1 0\ns 0 0 0 1\n",
               "6: expected a number for p's vertex, got 's'"},
        BadNff{"cone without radius", kV + "c 0 0 0 0 0 1 0 0\n",
               "2: a cone needs a non-zero radius"},
        BadNff{"cone of no length", kV + "c 0 0 0 1\n0 0 0 1\n",
               "3: a cone's base and apex must differ"},
        BadNff{"Ks over 1", kV + "f 1 1 1 0.5 2 3 0 1\n", "2: f's Ks: must be between 0 and 1"},
        BadNff{"T over 1", kV + "f 1 1 1 0.5 0.5 3 1.5 1\n", "2: f's T: must be between 0 and 1"},
        BadNff{"glass of index 0", kV + "f 1 1 1 0.5 0.5 3 0.9 0\n",
               "2: f's index of refraction: must be above 0"},
        BadNff{"negative colour", kV + "b -1 0 0\n", "2: b's background: colour components must not be negative"},
        BadNff{"view out of order", "v\nfrom 0 0 1\nup 0 1 0\n",
               "3: the view ('v', line 1) needs 'at' here, got 'up'"},
        BadNff{"view cut short", "v\nfrom 0 0 1\nat 0 0 0\n",
               "3: the view ('v', line 1) needs 'up' here, but the file ends"},
        BadNff{"eye at target", "v from 1 1 1 at 1 1 1 up 0 1 0 angle 40 hither 1 resolution 8 8",
               "1: v's from and at: eye and look_at must differ"},
        BadNff{"up along view", "v from 0 0 1 at 0 0 0 up 0 0 2 angle 40 hither 1 resolution 8 8",
               "1: v's up: up is parallel to the viewing direction"},
        BadNff{"angle 180", "v from 0 0 1 at 0 0 0 up 0 1 0 angle 180 hither 1 resolution 8 8",
               "1: v's angle: must be an angle in degrees strictly between 0 and 180"},
        BadNff{"resolution 0", "v from 0 0 1 at 0 0 0 up 0 1 0 angle 40 hither 1\nresolution 0 8",
               "2: v's resolution: must be between 1 and 16384, got 0"},
        BadNff{"two views", kV + kV, "2: a second view"}),
    [](const auto& info) { return testing::test_name(info.param.what); });

// Every SPD scene copied into tests/data loads, with the counts its README gives.
TEST(Nff, SpdScenesLoadWithTheirPrimitiveCounts) {
    const std::string dir = GLINT_SOURCE_DIR "/tests/data/spd/";
    const Scene balls = load_scene(dir + "balls-1.nff");
    EXPECT_EQ(balls.objects.size(), 10u + 1u); // 10 spheres, the floor polygon as a mesh
    EXPECT_EQ(balls.lights.size(), 3u);
    const Scene gears = load_scene(dir + "gears-1.nff");
    std::size_t triangles = 0;
    for (const TriangleMesh& m : gears.meshes) triangles += m.triangles.size();
    // 147 polygons: the floor, two 144-vertex faces (142 triangles each), 144 quads.
    EXPECT_EQ(triangles, 2u + 2u * 142u + 144u * 2u);
    const Scene rings = load_scene(dir + "rings-1.nff");
    std::size_t tubes = 0;
    for (const SceneObject& o : rings.objects) tubes += o.shape == ShapeKind::cylinder && o.open;
    EXPECT_EQ(tubes, 30u);
}

} // namespace
} // namespace glint
