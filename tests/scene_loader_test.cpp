// The JSON scene loader: documented defaults, and every class of bad input rejected with the
// file, the JSON path (or line and column) and what is wrong.
#include "test_scenes.h"

#include "io/nff_loader.h"
#include "io/scene_check.h"

#include <gtest/gtest.h>

#include <limits>

namespace glint {
namespace {

TEST(SceneLoader, AnEmptyObjectGivesTheDocumentedDefaults) {
    const Scene s = parse_scene("{}", "empty.json");
    EXPECT_EQ(s.camera.eye, DVec3(0, 0, 5));
    EXPECT_EQ(s.camera.look_at, DVec3(0, 0, 0));
    EXPECT_EQ(s.camera.up, DVec3(0, 1, 0));
    EXPECT_EQ(s.camera.fov_y, 45);
    EXPECT_EQ(s.camera.width, 800);
    EXPECT_EQ(s.camera.height, 600);
    EXPECT_EQ(s.background, Vec3(0.0f));
    EXPECT_EQ(s.ambient, Vec3(0.0f));
    EXPECT_EQ(s.render.max_depth, 5);
    EXPECT_FLOAT_EQ(s.render.min_reflectivity, 0.01f);
    EXPECT_TRUE(s.objects.empty());
    EXPECT_TRUE(s.lights.empty());
}

TEST(SceneLoader, MaterialDefaultsFollowTheDesign) {
    const Scene s = parse_scene(R"({"materials": {"a": {}, "b": {"diffuse": [0.1, 0.2, 0.3]}},
        "lights": [{"position": [1, 2, 3]}],
        "objects": [{"shape": "sphere"}, {"shape": "box", "material": "b"}]})",
                                "m.json");
    const Material& a = s.materials[1];
    EXPECT_EQ(a.diffuse, Vec3(0.8f));
    EXPECT_EQ(a.ambient, Vec3(0.8f)); // ambient defaults to diffuse
    EXPECT_EQ(a.specular, Vec3(0.0f));
    EXPECT_EQ(a.shininess, 32.0f);
    EXPECT_EQ(a.reflectivity, 0.0f);
    EXPECT_EQ(s.materials[2].ambient, Vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(s.objects[0].material, 0u); // the built-in default material
    EXPECT_EQ(s.objects[1].material, 2u);
    EXPECT_EQ(s.lights[0].color, Vec3(1.0f));
}

TEST(SceneLoader, MeshIndicesMayBeFlatOrTriples) {
    const Scene s = parse_scene(R"({"objects": [
        {"shape": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "indices": [0,1,2, 0,2,3]},
        {"shape": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], "indices": [[0,1,2],[0,2,3]]}]})",
                                "mesh.json");
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].triangles, s.meshes[1].triangles);
    EXPECT_EQ(s.meshes[0].triangles.size(), 2u);
}

struct BadScene {
    const char* what;
    const char* json;
    const char* message; // expected in the error, after "bad.json: "
};

void PrintTo(const BadScene& bad, std::ostream* out) {
    *out << bad.what;
}

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, IsRejectedWithFileAndPlace) {
    const BadScene& bad = GetParam();
    try {
        parse_scene(bad.json, "bad.json");
        FAIL() << bad.what << ": accepted";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("bad.json", 0), 0u) << what;
        EXPECT_NE(what.find(bad.message), std::string::npos) << bad.what << ": got " << what;
    }
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(EveryClass, BadSceneTest, ::testing::Values(
    BadScene{"malformed JSON", "{\n  \"objects\": [,]\n}", "bad.json:2:15: malformed JSON"},
    BadScene{"truncated JSON", "{\"objects\": [", "malformed JSON"},
    BadScene{"not an object", "[1, 2]", "/: expected an object, got an array"},
    BadScene{"unknown top-level key", R"({"objcts": []})", "/objcts: unknown key 'objcts'"},
    BadScene{"unknown object key", R"({"objects": [{"shape": "sphere", "colour": 1}]})", "/objects/0/colour: unknown key"},
    BadScene{"unknown camera key", R"({"camera": {"fov": 30}})", "/camera/fov: unknown key"},
    BadScene{"wrong type", R"({"camera": {"fov_y": "wide"}})", "/camera/fov_y: expected a number, got a string"},
    BadScene{"vector too short", R"({"camera": {"eye": [1, 2]}})", "/camera/eye: expected an array of 3 numbers, got an array of 2"},
    BadScene{"number beyond double", R"({"ambient": [0, 1e999, 0]})", "bad.json:1:17: number overflow parsing '1e999' (numbers must be finite"},
    BadScene{"negative colour", R"({"background": [0, -0.1, 0]})", "/background/1: colour components must not be negative"},
    BadScene{"colour beyond float's comfort", R"({"lights": [{"position": [0, 9, 0], "color": [1e308, 1, 1]}]})", "/lights/0/color/0: colour components must be at most 1e6"},
    BadScene{"missing material", R"({"materials": {"red": {}}, "objects": [{"shape": "sphere", "material": "blue"}]})",
             "/objects/0/material: no material named 'blue' (known: default, red)"},
    BadScene{"zero scale", R"({"objects": [{"shape": "sphere", "transform": [{"scale": [1, 0, 1]}]}]})",
             "/objects/0/transform/0/scale: components must be non-zero"},
    BadScene{"near-singular matrix", R"({"objects": [{"shape": "box", "transform": [{"matrix":
             [[1, 1, 0, 0], [1, 1.0000001, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]}]})", "/objects/0/transform: transform is"},
    BadScene{"projective matrix", R"({"objects": [{"shape": "box", "transform": [{"matrix":
             [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0.5, 0, 1]]}]}]})", "/objects/0/transform/0/matrix/3: the last row"},
    BadScene{"two operations in one entry", R"({"objects": [{"shape": "box", "transform": [{"scale": 2, "translate": [0, 0, 0]}]}]})",
             "/objects/0/transform/0: each transform entry has exactly one of"},
    BadScene{"rotation about nothing", R"({"objects": [{"shape": "box", "transform": [{"rotate": {"axis": [0, 0, 0], "degrees": 5}}]}]})",
             "/objects/0/transform/0/rotate/axis: must not be zero"},
    BadScene{"unknown shape", R"({"objects": [{"shape": "torus"}]})", "/objects/0/shape: unknown shape 'torus'"},
    BadScene{"missing shape", R"({"objects": [{}]})", "/objects/0: an object needs a shape"},
    BadScene{"fov out of range", R"({"camera": {"fov_y": 180}})", "/camera/fov_y: must be an angle in degrees strictly between 0 and 180"},
    BadScene{"width out of range", R"({"camera": {"width": 0}})", "/camera/width: must be between 1 and 16384, got 0"},
    BadScene{"fractional height", R"({"camera": {"height": 10.5}})", "/camera/height: must be a whole number"},
    BadScene{"camera beyond float's comfort", R"({"camera": {"eye": [1e300, 0, 0]}})", "/camera/eye/0: coordinates must be within ±1e15"},
    BadScene{"object placed beyond float's comfort", R"({"objects": [{"shape": "mesh", "vertices": [[1e15,0,0],[0,1,0],[0,0,1]], "indices": [0, 1, 2], "transform": [{"scale": 1e15}]}]})",
             "/objects/0/transform: the placed object reaches 1e+30 from the origin; objects must lie within ±1e15"},
    BadScene{"light beyond float's comfort", R"({"lights": [{"position": [0, -2e15, 0]}]})", "/lights/0/position/1: coordinates must be within ±1e15"},
    BadScene{"eye on look_at", R"({"camera": {"eye": [1, 1, 1], "look_at": [1, 1, 1]}})", "/camera: eye and look_at must differ"},
    BadScene{"up along view", R"({"camera": {"eye": [0, 5, 0], "look_at": [0, 0, 0]}})", "/camera: up is parallel to the viewing direction"},
    BadScene{"reflectivity above 1", R"({"materials": {"m": {"reflectivity": 1.5}}})", "/materials/m/reflectivity: must be between 0 and 1, got 1.5"},
    BadScene{"depth beyond limit", R"({"render": {"max_depth": 1000000000}})", "/render/max_depth: must be between 0 and 64"},
    BadScene{"unknown light type", R"({"lights": [{"type": "spot", "position": [0, 0, 0]}]})", "/lights/0/type: unknown light type 'spot'"},
    BadScene{"light without position", R"({"lights": [{}]})", "/lights/0: a light needs a position"},
    BadScene{"open sphere", R"({"objects": [{"shape": "sphere", "open": true}]})", "/objects/0/open: only cylinders and cones can be open"},
    BadScene{"open as a number", R"({"objects": [{"shape": "cone", "open": 1}]})", "/objects/0/open: expected true or false, got a number"},
    BadScene{"transmission over 1", R"({"materials": {"g": {"transmission": 1.2}}})", "/materials/g/transmission: must be between 0 and 1"},
    BadScene{"ior of 0", R"({"materials": {"g": {"transmission": 0.9, "ior": 0}}})", "/materials/g/ior: must be above 0"},
    BadScene{"infinite ior", R"({"materials": {"g": {"ior": 1e999}}})", "bad.json:1:29: number overflow"},
    BadScene{"huge ior", R"({"materials": {"g": {"ior": 1e300}}})", "/materials/g/ior: must be above 0 and at most 100"},
    BadScene{"ior as a string", R"({"materials": {"g": {"ior": "glass"}}})", "/materials/g/ior: expected a number, got a string"},
    BadScene{"checker of size 0", R"({"materials": {"c": {"checker": {"size": 0, "diffuse": [1, 1, 1]}}}})", "/materials/c/checker/size: must be above 0"},
    BadScene{"checker without a colour", R"({"materials": {"c": {"checker": {"size": 1}}}})", "/materials/c/checker: a checker needs a diffuse colour"},
    BadScene{"checker key unknown", R"({"materials": {"c": {"checker": {"size": 1, "diffuse": [1, 1, 1], "specular": 1}}}})", "/materials/c/checker/specular: unknown key"},
    BadScene{"both weight cut-offs", R"({"render": {"min_weight": 0.1, "min_reflectivity": 0.1}})", "/render/min_reflectivity: give min_weight or min_reflectivity"},
    BadScene{"top_radius on a sphere", R"({"objects": [{"shape": "sphere", "top_radius": 0.5}]})", "/objects/0/top_radius: only cones"},
    BadScene{"negative top_radius", R"({"objects": [{"shape": "cone", "top_radius": -1}]})", "/objects/0/top_radius: must be between 0"},
    BadScene{"index out of range", R"({"objects": [{"shape": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0, 1, 3]}]})",
             "/objects/0/indices/2: must be between 0 and 2, got 3"},
    BadScene{"indices not in threes", R"({"objects": [{"shape": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0, 1]}]})",
             "/objects/0/indices: needs a positive multiple of 3 indices, got 2"},
    BadScene{"triangle with four vertices", R"({"objects": [{"shape": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}]})",
             "/objects/0/vertices: a triangle has exactly 3 vertices"},
    BadScene{"collinear triangle", R"({"objects": [{"shape": "triangle", "vertices": [[0,0,0],[1,1,1],[2,2,2]]}]})",
             "/objects/0/vertices: the triangle's vertices are collinear"},
    BadScene{"missing mesh file", R"({"objects": [{"shape": "mesh", "file": "bunny.obj"}]})",
             "/objects/0/file: bunny.obj: cannot open mesh file"},
    BadScene{"mesh file on a sphere", R"({"objects": [{"shape": "sphere", "file": "bunny.obj"}]})",
             "/objects/0/file: only meshes are read from files"},
    BadScene{"key with a slash is escaped in the path", R"({"materials": {"a/b": {"shine": 1}}})", "/materials/a~1b/shine: unknown key"}
), [](const auto& info) { return testing::test_name(info.param.what); });
// clang-format on

TEST(SceneLoader, BracketsInsideStringsDoNotCountAsNesting) {
    const std::string brackets(1000, '[');
    EXPECT_NO_THROW(parse_scene(R"({"description": ")" + brackets + R"(\"["})", "ok.json"));
}

TEST(SceneLoader, MoreLightsThanTheLimitAreRefused) {
    std::string lights;
    for (std::size_t i = 0; i <= kMaxLights; ++i)
        lights += std::string(i ? "," : "") + R"({"position": [0, 9, 0]})";
    try {
        parse_scene(R"({"lights": [)" + lights + "]}", "many.json");
        FAIL() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(), "many.json: /lights: has 4097 lights; the limit is 4096");
    }
}

TEST(SceneLoader, MissingFileNamesTheFile) {
    try {
        load_scene("no/such/scene.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("no/such/scene.json: cannot open scene file"),
                  std::string::npos);
    }
}

TEST(SceneLoader, EveryShippedSceneLoads) {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        EXPECT_NO_THROW(load_scene(entry.path())) << entry.path();
        ++count;
    }
    EXPECT_GE(count, 5);
}

} // namespace
} // namespace glint

namespace glint {
namespace {

// Objects' optional names (`glint explain` shows them) line up with the objects, unnamed ones
// empty; a name must be a string.
TEST(SceneLoader, ObjectNamesLineUpWithTheObjects) {
    const Scene scene = parse_scene(R"({"objects": [
        {"shape": "sphere"}, {"name": "box", "shape": "box"}, {"shape": "plane"},
        {"name": "disk", "shape": "disk"}]})",
                                    "names.json");
    EXPECT_EQ(scene.object_names, (std::vector<std::string>{"", "box", "", "disk"}));
    EXPECT_THROW(parse_scene(R"({"objects": [{"name": 3, "shape": "sphere"}]})", "n.json"),
                 SceneError);
}

} // namespace
} // namespace glint

namespace glint {
namespace {

// io/scene_check.h: the rules hold a Scene whatever made it; the loader only names places.
// A scene built in code, broken one part at a time, is refused with the place its ScenePlaces
// gives for the part's model path, and the same rule reads the same in JSON and NFF.
TEST(SceneCheck, EachRuleNamesThePartsModelPathThroughTheLoadersPlaces) {
    const ScenePlaces places = [](const std::string& path) { return "here: " + path; };
    const auto refusal = [&](const Scene& scene) {
        try {
            check_scene(scene, places);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    Scene scene;
    scene.materials.push_back(Material{});
    EXPECT_EQ(refusal(scene), "accepted");
    Scene bad = scene;
    bad.camera.look_at = bad.camera.eye;
    EXPECT_EQ(refusal(bad), "here: camera: eye and look_at must differ");
    bad = scene;
    bad.lights.push_back({DVec3(0, 2e15, 0), glm::vec3(1)});
    EXPECT_EQ(refusal(bad), "here: lights/0/position/1: coordinates must be within ±1e15");
    bad = scene;
    bad.materials[0].transmission = 0.5f, bad.materials[0].ior = 0;
    EXPECT_EQ(refusal(bad), "here: materials/0/ior: must be above 0 and at most 100");
    bad = scene;
    bad.render.samples = 17;
    EXPECT_EQ(refusal(bad), "here: render/samples: must be between 1 and 16, got 17");
    bad = scene;
    bad.meshes.push_back(
        {{glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}, {{0, 1, 3}}, {}, {}, {}, {}, {}});
    EXPECT_EQ(refusal(bad), "here: meshes/0/indices/2: must be between 0 and 2, got 3");
    for (const float y : {3e15f, std::numeric_limits<float>::quiet_NaN()}) {
        bad = scene;
        bad.meshes.push_back({{glm::vec3(0), glm::vec3(1, y, 0), glm::vec3(0, 1, 0)},
                              {{0, 1, 2}},
                              {},
                              {},
                              {},
                              {},
                              {}});
        EXPECT_EQ(refusal(bad), "here: meshes/0/vertices/1/1: coordinates must be within ±1e15");
    }
    bad = scene;
    SceneObject far;
    far.transform = translation_matrix(DVec3(0, 0, 9e14)) * scale_matrix(DVec3(2e14));
    bad.objects.push_back(far);
    EXPECT_EQ(refusal(bad), "here: objects/0/transform: the placed object reaches 1.1e+15 from "
                            "the origin; objects must lie within ±1e15");

    // The same rule from both formats: only the place differs.
    const std::string json_error = [&] {
        try {
            parse_scene(R"({"materials": {"m": {"reflectivity": 2}}})", "s.json");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string();
    }();
    const std::string nff_error = [&] {
        try {
            parse_nff("v from 0 0 1 at 0 0 0 up 0 1 0 angle 40 hither 1 resolution 8 8\n"
                      "f 1 1 1 0.5 2 3 0 1\n",
                      "s.nff");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string();
    }();
    EXPECT_EQ(json_error, "s.json: /materials/m/reflectivity: must be between 0 and 1, got 2");
    EXPECT_EQ(nff_error, "s.nff:2: f's Ks: must be between 0 and 1, got 2");
}

} // namespace
} // namespace glint
