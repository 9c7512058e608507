// OBJ import: meshes, normals and MTL materials read, concave faces triangulated, the same file
// placed many times stored once, and every malformed line reported with its file and line.
#include "test_scenes.h"

#include "io/load_scene.h"
#include "io/obj_loader.h"
#include "io/polygon.h"
#include "trace/world.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace glint {
namespace {

const std::string kMeshes = GLINT_SOURCE_DIR "/scenes/meshes/";

TEST(Obj, ReadsVertexNormalsAndTheMtlMaterial) {
    const ObjModel model = load_obj(kMeshes + "geosphere.obj");
    ASSERT_EQ(model.parts.size(), 1u);
    const ObjPart& part = model.parts[0];
    EXPECT_EQ(part.mesh.triangles.size(), 320u);
    EXPECT_EQ(part.mesh.vertices.size(), 162u); // one per (position, normal) pair used
    ASSERT_EQ(part.mesh.normals.size(), part.mesh.vertices.size());
    for (std::size_t i = 0; i < part.mesh.vertices.size(); ++i)
        EXPECT_NEAR(glm::length(part.mesh.normals[i] - part.mesh.vertices[i]), 0, 1e-5);
    ASSERT_TRUE(part.material.has_value());
    EXPECT_EQ(part.material_name, "copper");
    EXPECT_EQ(part.material->diffuse, glm::vec3(0.75f, 0.4f, 0.2f));
    EXPECT_EQ(part.material->specular, glm::vec3(0.5f));
    EXPECT_EQ(part.material->shininess, 40.0f);
    EXPECT_TRUE(model.notes.empty());
}

// The star's 10-vertex faces are concave: a fan from the first vertex would cover the notches.
TEST(Obj, ConcaveFacesAreEarClippedAndWithoutNormalsShadeFlat) {
    const ObjModel model = load_obj(kMeshes + "star.obj");
    ASSERT_EQ(model.parts.size(), 1u);
    const TriangleMesh& mesh = model.parts[0].mesh;
    EXPECT_TRUE(mesh.normals.empty());
    EXPECT_FALSE(model.parts[0].material.has_value());
    EXPECT_EQ(mesh.triangles.size(), 2u * 8u + 10u * 2u);
    std::vector<glm::dvec3> top;
    for (int i = 0; i < 10; ++i) top.emplace_back(mesh.vertices[i]);
    double area = 0;
    for (const glm::uvec3& t : mesh.triangles)
        if (t.x < 10 && t.y < 10 && t.z < 10)
            area += glm::cross(top[t.y] - top[t.x], top[t.z] - top[t.x]).z / 2;
    EXPECT_NEAR(area, newell_normal(top).z / 2, 1e-6);
}

TEST(Obj, ScenePlacingAFileManyTimesStoresItsMeshOnce) {
    const Scene scene = load_scene(GLINT_SOURCE_DIR "/scenes/instances.json");
    EXPECT_EQ(scene.meshes.size(), 2u); // geosphere and star, each read once
    std::size_t spheres = 0;
    for (const SceneObject& o : scene.objects) spheres += o.shape == ShapeKind::mesh && o.mesh == 0;
    EXPECT_EQ(spheres, 7u);
    // The MTL material where the scene names none; the scene's where it does.
    const auto named = [&](const std::string& name) {
        return static_cast<std::uint32_t>(
            std::find(scene.material_names.begin(), scene.material_names.end(), name) -
            scene.material_names.begin());
    };
    EXPECT_EQ(scene.objects[1].material, named("meshes/geosphere.obj:copper"));
    EXPECT_EQ(scene.objects.back().material, named("mirror"));
    // World prepares each mesh once; the instances differ only in their transforms.
    const World world(scene);
    EXPECT_EQ(world.objects()[1].params.mesh, world.objects().back().params.mesh);
}

ObjModel parse(const std::string& text) {
    return parse_obj(text, "m.obj", [](const std::string&) { return std::nullopt; });
}

struct BadObj {
    const char* what;
    std::string text;
    const char* message; // expected in the error
};

void PrintTo(const BadObj& bad, std::ostream* out) {
    *out << bad.what;
}

class ObjErrorTest : public ::testing::TestWithParam<BadObj> {};

TEST_P(ObjErrorTest, NamesTheFileAndLine) {
    try {
        parse(GetParam().text);
        FAIL() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(GetParam().message), std::string::npos) << e.what();
    }
}

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    Bad, ObjErrorTest,
    ::testing::Values(
        BadObj{"bad number", "v 0 0 0\nv 1 x 0\n", "m.obj:2: expected a number in v, got 'x'"},
        BadObj{"too few coordinates", "v 0 0\n", "m.obj:1: v needs 3 to 7 numbers, got 2"},
        BadObj{"huge", "v 1e300 0 0\n", "m.obj:1: coordinate beyond 1e15"},
        BadObj{"index too large", kTri + "f 1 2 4\n",
               "m.obj:4: vertex index 4 is beyond the 3 vertices defined so far"},
        BadObj{"index zero", kTri + "f 0 1 2\n", "m.obj:4: expected a vertex index"},
        BadObj{"negative too far", kTri + "f -1 -2 -4\n", "m.obj:4: vertex index -4 is beyond"},
        BadObj{"normal missing", kTri + "f 1//1 2//1 3//1\n",
               "m.obj:4: normal index 1 is beyond the 0 normals"},
        BadObj{"two corners", kTri + "f 1 2\n", "m.obj:4: a face needs at least 3 vertices"},
        BadObj{"four parts", kTri + "f 1/1/1/1 2 3\n",
               "m.obj:4: a face corner has at most 3 parts"},
        BadObj{"unknown statement", kTri + "\n\nbogus 1 2\n", "m.obj:6: unknown statement 'bogus'"},
        BadObj{"binary", std::string("v 0 0 0\n\x01\x02\x03\n", 11), "m.obj:2: unknown statement"},
        BadObj{"no faces", kTri, "m.obj:4: no faces"}),
    [](const auto& info) { return testing::test_name(info.param.what); });

// An OBJ whose one library is `mtl`.
ObjModel parse_with_mtl(const std::string& text, const std::string& mtl) {
    return parse_obj(text, "m.obj", [&](const std::string&) { return mtl; });
}

TEST(Obj, MtlIllumAndDissolveMapToReflectionAndTransmission) {
    const std::string faces = "mtllib m.mtl\n" + kTri + "usemtl glass\nf 1 2 3\n";
    const ObjModel glass = parse_with_mtl(
        faces, "newmtl glass\nKd 0.1 0.2 0.3\nKs 0.3 0.3 0.6\nNs 50\nillum 7\nNi 1.3\nd 0.2\n");
    ASSERT_EQ(glass.parts.size(), 1u);
    ASSERT_TRUE(glass.parts[0].material.has_value());
    const Material m = *glass.parts[0].material;
    EXPECT_EQ(m.diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(m.reflectivity, 0.4f); // the mean of Ks
    EXPECT_FLOAT_EQ(m.transmission, 0.8f); // 1 − d
    EXPECT_FLOAT_EQ(m.ior, 1.3f);
    const Material clear =
        *parse_with_mtl(faces, "newmtl glass\nillum 4\nNi 1.5\n").parts[0].material;
    EXPECT_FLOAT_EQ(clear.transmission, 1.0f) << "refracting illum with d = 1: all of it";
    const Material plain =
        *parse_with_mtl(faces, "newmtl glass\nKs 0.5 0.5 0.5\nillum 2\n").parts[0].material;
    EXPECT_EQ(plain.reflectivity, 0.0f) << "illum 2 is a highlight, not a mirror";
    EXPECT_EQ(plain.transmission, 0.0f);
    try {
        parse_with_mtl(faces, "newmtl glass\nillum 7\nNi 0\n");
        FAIL() << "accepted an index of refraction of 0";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("m.obj: material 'glass': Ni"), std::string::npos)
            << e.what();
    }
}

TEST(Obj, NegativeIndicesCountBack) {
    const ObjModel model = parse(kTri + "f -3 -2 -1\n");
    ASSERT_EQ(model.parts.size(), 1u);
    EXPECT_EQ(model.parts[0].mesh.triangles.size(), 1u);
}

// A material library that is missing or malformed is an error naming the file and line, as a
// bad OBJ line is (issue: "a missing or malformed .mtl: exit 2 with the file and the line").
// A missing library is what a model only decorates itself with: a warning, default material.
TEST(Obj, AMissingMaterialLibraryIsAWarningAndTheFacesGetTheDefaultMaterial) {
    const ObjModel model = parse_obj(kTri + "mtllib m.mtl\nusemtl x\nf 1 2 3\n", "dir/m.obj",
                                     [](const std::string&) { return std::optional<std::string>(); });
    ASSERT_EQ(model.parts.size(), 1u);
    EXPECT_FALSE(model.parts[0].material.has_value());
    ASSERT_EQ(model.warnings.size(), 1u);
    EXPECT_EQ(model.warnings[0],
              "dir/m.obj:4: material library 'm.mtl' cannot be read: its materials are the "
              "default one");
}

TEST(Obj, AMalformedMaterialLibraryNamesItsFileAndLine) {
    const auto error = [](const std::string& obj, const std::optional<std::string>& mtl) {
        try {
            parse_obj(obj, "dir/m.obj", [&](const std::string&) { return mtl; });
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string obj = kTri + "mtllib m.mtl\nusemtl x\nf 1 2 3\n";
    EXPECT_EQ(error(obj, "newmtl x\nKd 1 \x1b[2J 1\n"),
              "dir/m.obj: dir/m.mtl:2: expected a number in Kd, got '\\x1b[2J'");
    EXPECT_EQ(error(obj, "newmtl x\nKd 1 0.5 zero\n"),
              "dir/m.obj: dir/m.mtl:2: expected a number in Kd, got 'zero'");
    EXPECT_EQ(error(obj, "newmtl x\nKd 1 1\n"), "dir/m.obj: dir/m.mtl:2: Kd needs 3 numbers, got 2");
    EXPECT_EQ(error(obj, "# a comment\nKd 1 1 1\n"), "dir/m.obj: dir/m.mtl:2: Kd before any newmtl");
    EXPECT_EQ(error(obj, "newmtl x\nglossiness 3\n"),
              "dir/m.obj: dir/m.mtl:2: unknown MTL statement 'glossiness'");
    EXPECT_EQ(error(obj, "newmtl\n"), "dir/m.obj: dir/m.mtl:1: newmtl needs a material name");
    EXPECT_EQ(error(obj, "newmtl x\nKd 1 1 1\nmap_Kd wood.png\nNs 10 # shiny\r\n"), "accepted");
}

TEST(Obj, TinyobjloaderReadsOnlyTheStatementsThatWereChecked) {
    // Found by fuzz_obj (a heap overflow under ASan): the checker cut "f 1 2 3# 4 5 99" at the
    // '#', but tinyobjloader, which takes '#' as a comment only at the start of a line, read
    // index 99 of 3 vertices. It likewise ends a line at a lone '\r', so a face hidden in a
    // group name reached it unchecked. It now reads the checked text.
    const ObjModel comment = parse(kTri + "f 1 2 3# 4 5 99\n");
    ASSERT_EQ(comment.parts.size(), 1u);
    EXPECT_EQ(comment.parts[0].mesh.triangles.size(), 1u);
    const ObjModel carriage_return = parse(kTri + "g a\rf 1 2 99\nf 1 2 3\n");
    ASSERT_EQ(carriage_return.parts.size(), 1u);
    EXPECT_EQ(carriage_return.parts[0].mesh.triangles.size(), 1u);
}

// From a JSON scene: the error names the scene, the object's file key, then the OBJ and line.
TEST(Obj, ErrorsThroughASceneNameBothFiles) {
    const auto dir = std::filesystem::temp_directory_path() / "glint_obj_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "bad.obj") << kTri << "f 1 2 9\n";
    std::ofstream(dir / "s.json") << R"({"objects": [{"shape": "sphere"},
        {"shape": "mesh", "file": "bad.obj"}]})";
    std::ofstream(dir / "missing.json") << R"({"objects": [{"shape": "mesh", "file": "no.obj"}]})";
    std::ofstream(dir / "mixed.json")
        << R"({"objects": [{"shape": "mesh", "file": "bad.obj", "indices": [0, 1, 2]}]})";
    const auto error = [](const std::filesystem::path& p) {
        try {
            load_scene(p);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string bad = error(dir / "s.json");
    EXPECT_NE(bad.find("s.json: /objects/1/file: "), std::string::npos) << bad;
    EXPECT_NE(bad.find("bad.obj:4: vertex index 9 is beyond"), std::string::npos) << bad;
    EXPECT_NE(error(dir / "missing.json").find("/objects/0/file: "), std::string::npos);
    EXPECT_NE(error(dir / "missing.json").find("no.obj: cannot open mesh file"), std::string::npos);
    EXPECT_NE(error(dir / "mixed.json").find("either a file or vertices and indices"),
              std::string::npos);
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace glint
