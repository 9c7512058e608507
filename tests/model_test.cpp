// Models as scenes (docs/SCENES.md, "Models as scenes", "glTF", "Textures"): an OBJ with no
// scene is framed and lit; textures show each texel where it should be, the same in both modes;
// a glTF's sampler and coordinates are read; bad glTF input exits 2 naming the file and the
// place, while what a model only decorates itself with is a warning.
#include "gltf_builder.h"
#include "rgba_png.h"
#include "run_glint.h"

#include "io/error.h"
#include "io/gltf_loader.h"
#include "io/model_scene.h"
#include "io/png.h"
#include "trace/image.h"
#include "trace/shapes/table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/wait.h>

namespace glint {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::GltfBuilder;
using testing::glint;
using testing::Outcome;
using testing::write;

fs::path fresh_dir() {
    return testing::fresh_dir("glint_model");
}

// 4 × 4 texels, each a different colour: texel (x, y) is (60x + 15, 60y + 15, 255 − 40(x + y)).
Image texel_grid() {
    Image image(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(60 * x + 15);
            p[1] = static_cast<std::uint8_t>(60 * y + 15);
            p[2] = static_cast<std::uint8_t>(255 - 40 * (x + y));
        }
    return image;
}

// The shipped meshes, with no scene: the framing rule puts the model in the middle of the
// frame, covering a fair part of it (at least a sixth of the pixels, and half the height or
// width), and the default lights light it (no pixel of it black).
// model_sphere skips the objects whose placed box cannot change its answer (instances of a large
// mesh): on scenes of shared, randomly placed meshes and boxes its answer is, to the bit, the one
// every vertex and every box corner gives.
TEST(Model, TheModelSphereIsTheOneEveryPointGives) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int round = 0; round < 20; ++round) {
        std::vector<TriangleMesh> meshes(3);
        for (TriangleMesh& m : meshes) {
            for (int v = 0; v < 50; ++v)
                m.vertices.emplace_back(u(rng), u(rng) * 0.3, u(rng) * 2);
            m.triangles.push_back({0, 1, 2});
        }
        std::vector<SceneObject> objects;
        for (int k = 0; k < 200; ++k) {
            SceneObject o;
            o.shape = k % 7 == 0 ? ShapeKind::box : ShapeKind::mesh;
            o.mesh = static_cast<std::uint32_t>(k % 3);
            o.transform = translation_matrix({10 * u(rng), 3 * u(rng), 10 * u(rng)}) *
                          rotation_matrix({u(rng), u(rng), u(rng) + 2}, 180 * u(rng)) *
                          scale_matrix(DVec3(1 + 0.5 * u(rng)));
            objects.push_back(o);
        }
        // Every point, written out again.
        std::vector<DVec3> points;
        for (const SceneObject& o : objects)
            if (o.shape == ShapeKind::mesh) {
                for (const glm::vec3& v : meshes[o.mesh].vertices)
                    points.push_back(DVec3(o.transform * glm::dvec4(DVec3(v), 1.0)));
            } else {
                const auto [a, b] = transformed_box(*unit_box(o, meshes), o.transform);
                for (int k = 0; k < 8; ++k)
                    points.emplace_back(k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z);
            }
        DVec3 lo(points[0]), hi(points[0]);
        for (const DVec3& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const DVec3 centre = 0.5 * (lo + hi);
        double radius = 0;
        for (const DVec3& p : points) radius = std::max(radius, glm::length(p - centre));
        const std::optional<ModelSphere> sphere = model_sphere(objects, meshes);
        ASSERT_TRUE(sphere);
        EXPECT_EQ(sphere->centre, centre) << "round " << round;
        EXPECT_EQ(sphere->radius, radius) << "round " << round;
    }
}

TEST(Model, AnObjWithNoSceneIsFramedToFillAFairPartOfTheImage) {
    const fs::path dir = fresh_dir();
    for (const char* mesh : {"geosphere", "star"}) {
        const Outcome r = glint(dir, std::string("render '" GLINT_SOURCE_DIR "/scenes/meshes/") +
                                         mesh + ".obj' --mode ray --size 160x120 -o m.png");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Image image = read_png(dir / "m.png");
        int covered = 0, x0 = 160, x1 = -1, y0 = 120, y1 = -1;
        for (int y = 0; y < 120; ++y)
            for (int x = 0; x < 160; ++x) {
                const std::uint8_t* p = image.pixel(x, y);
                if (p[0] + p[1] + p[2] == 0) continue; // the background
                ++covered;
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
        EXPECT_GT(covered, 160 * 120 / 6) << mesh;
        EXPECT_TRUE(y1 - y0 >= 60 || x1 - x0 >= 80) << mesh;
        // Centred: the model's extent is balanced within a few pixels of the middle.
        EXPECT_NEAR((x0 + x1) / 2.0, 80, 12) << mesh;
        EXPECT_NEAR((y0 + y1) / 2.0, 60, 12) << mesh;
    }
}

// A quad that exactly fills a 90° frame at distance 1, one pixel per texel, lit by ambient light
// 1 alone: each pixel's colour is its texel's, byte for byte, in both modes.
TEST(Model, ATexturedQuadShowsEachTexelWhereItShouldInBothModes) {
    const fs::path dir = fresh_dir();
    write_png(dir / "grid.png", texel_grid());
    write(dir / "quad.mtl", "newmtl grid\nKd 1 1 1\nKs 0 0 0\nmap_Kd grid.png\n");
    write(dir / "quad.obj", "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl grid\nf 1/1 2/2 3/3 4/4\n");
    write(dir / "quad.json", R"({"camera": {"eye": [0, 0, 1], "look_at": [0, 0, 0], "fov_y": 90,
                                             "width": 4, "height": 4},
                                  "ambient": [1, 1, 1],
                                  "objects": [{"shape": "mesh", "file": "quad.obj"}]})");
    const Image grid = texel_grid();
    for (const char* mode : {"ray", "hybrid"}) {
        const Outcome r = glint(dir, std::string("render quad.json -o q.png --mode ") + mode);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Image image = read_png(dir / "q.png");
        EXPECT_EQ(image.rgb, grid.rgb) << mode;
    }
    // Larger, between texel centres (bilinear), and through explain: hybrid equals ray.
    ASSERT_EQ(glint(dir, "render quad.json --size 37x29 -o ray.png --mode ray").exit_code, 0);
    ASSERT_EQ(glint(dir, "render quad.json --size 37x29 -o hybrid.png --mode hybrid").exit_code, 0);
    EXPECT_EQ(read_png(dir / "ray.png").rgb, read_png(dir / "hybrid.png").rgb);
    const Outcome explain = glint(dir, "explain quad.json 1 2");
    ASSERT_EQ(explain.exit_code, 0) << explain.err;
    EXPECT_NE(explain.out.find("texture: grid.png (4 × 4) at uv (0.375, 0.625): texel position "
                              "(1.5, 2.5), nearest texel [1, 2], bilinear colour (0.2941, 0.5294, "
                              "0.5294)"),
              std::string::npos)
        << explain.out;
}

// OBJ cut-outs: a map_d of grey levels (black on the left half, white on the right; no alpha
// channel) cuts the quad out where its grey is below 0.5, in front of a red ground quad; the
// four quadrants of 4×4 texels each are seen through or not, in both modes alike.
TEST(Model, AnObjMapDCutsOutWhereItsGreyIsBelowOneHalf) {
    const fs::path dir = fresh_dir();
    Image mask(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) std::fill_n(mask.pixel(x, y), 3, std::uint8_t(x < 2 ? 0 : 255));
    write_png(dir / "mask.png", mask);
    write(dir / "quad.mtl", "newmtl leaf\nKd 0 1 0\nKs 0 0 0\nmap_d -clamp on mask.png\n"
                            "newmtl ground\nKd 1 0 0\nKs 0 0 0\n");
    write(dir / "quad.obj", "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                            "v -9 -9 -1\nv 9 -9 -1\nv 9 9 -1\nv -9 9 -1\n"
                            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl leaf\nf 1/1 2/2 3/3 4/4\n"
                            "usemtl ground\nf 5/1 6/2 7/3 8/4\n");
    write(dir / "quad.json", R"({"camera": {"eye": [0, 0, 1], "look_at": [0, 0, 0], "fov_y": 90,
                                             "width": 16, "height": 16},
                                  "ambient": [1, 1, 1],
                                  "objects": [{"shape": "mesh", "file": "quad.obj"}]})");
    for (const char* mode : {"ray", "hybrid"}) {
        const Outcome r = glint(dir, std::string("render quad.json -o q.png --mode ") + mode);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_EQ(r.err.find("map_d"), std::string::npos) << r.err; // read, not warned about
        const Image image = read_png(dir / "q.png");
        EXPECT_EQ(image.pixel(3, 8)[0], 255) << mode;  // through the cut-out: the red ground
        EXPECT_EQ(image.pixel(3, 8)[1], 0) << mode;
        EXPECT_EQ(image.pixel(12, 8)[1], 255) << mode; // the green leaf
        EXPECT_EQ(image.pixel(12, 8)[0], 0) << mode;
    }
}

// A glTF quad with a base colour texture stored in the buffer: the image is decoded, the
// sampler's wrap modes and TEXCOORD_0 are read, and hybrid equals ray byte for byte.
TEST(Model, AGltfTextureIsReadWithItsSamplerAndCoordinates) {
    const fs::path dir = fresh_dir();
    GltfBuilder b;
    const int texture = b.texture(encode_png(texel_grid()), {{"wrapS", 33071}, {"wrapT", 33648}});
    b.doc["materials"].push_back(
        {{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}}}});
    const int mesh = b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, 0,
                            {0, 1, 1, 1, 1, 0, 0, 0});
    b.node({{"mesh", mesh}});
    const Scene scene = parse_gltf(b.glb(), "quad.glb", {});
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].wrap_s, Wrap::clamp);
    EXPECT_EQ(scene.textures[0].wrap_t, Wrap::mirror);
    const Image grid = texel_grid();
    EXPECT_EQ(scene.textures[0].image->rgb,
              std::vector<std::uint8_t>(grid.rgb.begin(), grid.rgb.end()));
    EXPECT_EQ(scene.materials.at(1).texture, 0u);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].uvs.at(2), glm::vec2(1, 0));
    EXPECT_TRUE(scene.warnings.empty());
    write(dir / "quad.glb", b.glb());
    ASSERT_EQ(glint(dir, "render quad.glb --size 64x48 -o ray.png --mode ray").exit_code, 0);
    ASSERT_EQ(glint(dir, "render quad.glb --size 64x48 -o hybrid.png --mode hybrid").exit_code, 0);
    EXPECT_EQ(read_png(dir / "ray.png").rgb, read_png(dir / "hybrid.png").rgb);
}

// MASK, BLEND and emission as DESIGN §13 and docs/SCENES.md read them: a masked quad (alpha 0 on
// its left half) in front of an emissive one. The texture's alpha is kept beside its colour,
// the cut-off and factor on the material; through the left half the emissive quad shows, its
// red above what the default lights give a grey quad; hybrid equals ray byte for byte.
TEST(Model, AGltfMaskBlendAndEmissionAreReadAsTheDesignSays) {
    const fs::path dir = fresh_dir();
    GltfBuilder b;
    const int texture = b.texture(testing::rgba_png(2, 1, {255, 255, 255, 0, 255, 255, 255, 255}),
                                  {{"wrapS", 33071}, {"wrapT", 33071}});
    b.doc["materials"] = {
        {{"alphaMode", "MASK"},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}}}},
        {{"emissiveFactor", {1, 0.5, 0}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2}}}}},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.2, 0.2, 1}}, {"metallicFactor", 0}}}},
        {{"alphaMode", "BLEND"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.25}}, {"metallicFactor", 0}}}}};
    const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    const std::vector<std::uint32_t> corners = {0, 1, 2, 0, 2, 3};
    b.node({{"mesh", b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, corners, 0, uv)}});
    b.node({{"mesh", b.mesh({-2, -2, -1, 2, -2, -1, 2, 2, -1, -2, 2, -1}, corners, 1, uv)}});
    b.node({{"mesh", b.mesh({3, 3, -1, 4, 3, -1, 4, 4, -1}, {0, 1, 2}, 2)}});
    const Scene scene = parse_gltf(b.glb(), "cut.glb", {});
    EXPECT_TRUE(scene.warnings.empty());
    ASSERT_EQ(scene.materials.size(), 4u);
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].image->alpha, (std::vector<std::uint8_t>{0, 255}));
    const Material& mask = scene.materials[1];
    EXPECT_TRUE(mask.cut_out);
    EXPECT_EQ(mask.alpha, 1.0f);
    EXPECT_EQ(mask.alpha_cutoff, 0.5f);
    EXPECT_EQ(scene.materials[2].emission, glm::vec3(2, 1, 0));
    EXPECT_FALSE(scene.materials[2].cut_out);
    const Material& blend = scene.materials[3];
    EXPECT_FLOAT_EQ(blend.transmission, 0.75f);
    EXPECT_EQ(blend.ior, 1.0f);
    EXPECT_FLOAT_EQ(blend.diffuse.x, 0.25f);
    write(dir / "cut.glb", b.glb());
    ASSERT_EQ(glint(dir, "render cut.glb --size 64x48 -o ray.png --mode ray").exit_code, 0);
    ASSERT_EQ(glint(dir, "render cut.glb --size 64x48 -o hybrid.png --mode hybrid").exit_code, 0);
    const Image ray = read_png(dir / "ray.png");
    EXPECT_EQ(ray.rgb, read_png(dir / "hybrid.png").rgb);
    // The framed model's centre is off to the right (the blended triangle): find the masked
    // quad's middle row by the front quad's colour (white, lit) on its right half.
    int emissive = 0, white = 0;
    for (int y = 0; y < ray.height; ++y)
        for (int x = 0; x < ray.width; ++x) {
            const std::uint8_t* p = ray.pixel(x, y);
            emissive += p[0] == 255 && p[2] < 64;
            white += p[0] > 100 && p[0] == p[1] && p[1] == p[2];
        }
    EXPECT_GT(emissive, 20);
    EXPECT_GT(white, 20);
}

// --colour srgb: the glTF's base colour texture is decoded from sRGB (its bytes 188 are 0.5
// linear), the PNG is encoded again, and the EXR stays linear; the default is unchanged.
TEST(Model, ColourSrgbDecodesTexturesAndEncodesThePng) {
    const fs::path dir = fresh_dir();
    GltfBuilder b;
    Image grey(1, 1);
    std::fill(grey.rgb.begin(), grey.rgb.end(), std::uint8_t{188});
    const int texture = b.texture(encode_png(grey));
    b.doc["materials"].push_back(
        {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0}}}});
    const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    b.node({{"mesh", b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, 0, uv)}});
    write(dir / "grey.glb", b.glb());
    ModelOptions srgb;
    srgb.srgb = true;
    EXPECT_TRUE(parse_gltf(b.glb(), "grey.glb", {}, srgb).textures.at(0).srgb);
    EXPECT_FALSE(parse_gltf(b.glb(), "grey.glb", {}).textures.at(0).srgb);
    for (const char* args : {"--colour linear -o linear.png", "--colour srgb -o srgb.png",
                             "-o default.png", "--colour srgb -o srgb.exr",
                             "--colour linear -o linear.exr"}) {
        const Outcome r = glint(dir, std::string("render grey.glb --size 32x24 --mode ray ") + args);
        ASSERT_EQ(r.exit_code, 0) << args << r.err;
    }
    EXPECT_EQ(read_png(dir / "linear.png").rgb, read_png(dir / "default.png").rgb);
    const Image linear = read_png(dir / "linear.png"), encoded = read_png(dir / "srgb.png");
    EXPECT_NE(linear.rgb, encoded.rgb);
    const std::uint8_t* centre = encoded.pixel(16, 12);
    const std::uint8_t* plain = linear.pixel(16, 12);
    // The quad's lit grey: decoded to a darker linear value, then encoded brighter again.
    EXPECT_GT(centre[0], 0);
    EXPECT_NE(centre[0], plain[0]);
    const Outcome bad = glint(dir, "render grey.glb --colour rec709 -o x.png");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// What a glTF only decorates itself with (a texture file that is missing, features glint does
// not draw) is a warning; the model renders.
TEST(Model, AMissingTextureAndUnusedFeaturesAreWarnings) {
    const fs::path dir = fresh_dir();
    GltfBuilder b;
    b.doc["images"].push_back({{"uri", "missing.png"}});
    b.doc["textures"].push_back({{"source", 0}});
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                  {"extensions", {{"KHR_materials_sheen", json::object()}}}});
    b.node({{"mesh", b.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, 0, {0, 0, 1, 0, 0, 1})}});
    write(dir / "m.gltf", b.gltf());
    const Outcome r = glint(dir, "render m.gltf --size 32x24 -o m.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("glint: warning: m.gltf: /images/0: texture not used: cannot read "
                         "'missing.png'"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("extension KHR_materials_sheen (/materials/0)"), std::string::npos)
        << r.err;
}

// Bad input: each case exits 2 naming the file and the place, and writes nothing.
struct BadGltf {
    std::string what;
    std::function<std::string(GltfBuilder&)> make; // the file's bytes
    std::string message;
};

GltfBuilder triangle() {
    GltfBuilder b;
    b.node({{"mesh", b.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2})}});
    return b;
}

// The model's glTF text with the float at byte `at` of its buffer replaced by the bits `bits`.
std::string with_float(GltfBuilder& b, std::size_t at, std::uint32_t bits) {
    std::string bin = b.bin();
    std::memcpy(&bin[at], &bits, 4);
    json d = json::parse(b.gltf());
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + GltfBuilder::base64(bin);
    return d.dump();
}

// The triangle's primitive given material 0, whose fields are `material`.
std::string with_material(GltfBuilder& b, json material) {
    b.doc["materials"].push_back(std::move(material));
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b.gltf();
}

std::vector<BadGltf> bad_gltf() {
    return {
        {"missing buffer file", [](GltfBuilder& b) { return b.gltf_with_file("gone.bin"); },
         "bad.gltf: /buffers/0/uri: cannot read 'gone.bin'"},
        {"short buffer",
         [](GltfBuilder& b) {
             json d = json::parse(b.gltf());
             d["buffers"][0]["byteLength"] = 4096;
             return d.dump();
         },
         "bad.gltf: /buffers/0: its data URI holds 48 bytes, byteLength says 4096"},
        {"accessor beyond its view",
         [](GltfBuilder& b) {
             b.doc["accessors"][0]["count"] = 40;
             return b.gltf();
         },
         "bad.gltf: /accessors/0: 40 elements of 12 bytes, 12 apart from byte 0, run past the "
         "end of /bufferViews/0 (36 bytes)"},
        {"view beyond its buffer",
         [](GltfBuilder& b) {
             b.doc["bufferViews"][1]["byteOffset"] = 4000;
             return b.gltf();
         },
         "bad.gltf: /bufferViews/1: bytes 4000 to 4012 are beyond buffer 0's 48 bytes"},
        {"index out of range",
         [](GltfBuilder& b) {
             std::string bin = b.bin();
             bin[40] = 7; // the second index
             GltfBuilder c = b;
             json d = json::parse(b.gltf());
             d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + GltfBuilder::base64(bin);
             return d.dump();
         },
         "bad.gltf: /accessors/1: index 1 is 7, beyond the 3 vertices"},
        {"NaN position",
         [](GltfBuilder& b) { return with_float(b, 16, 0x7fc00000); }, // vertex 1's y
         "bad.gltf: /accessors/0, element 1: coordinates must be within ±1e15"},
        // The file has no camera, so the framing camera is made from the positions: the bad one
        // is still blamed on its accessor and element, not on the camera framed around it.
        {"infinite position",
         [](GltfBuilder& b) { return with_float(b, 12, 0x7f800000); }, // vertex 1's x
         "bad.gltf: /accessors/0, element 1: coordinates must be within ±1e15"},
        {"node cycle",
         [](GltfBuilder& b) {
             b.node({{"children", {0}}}, false);
             b.doc["nodes"][0]["children"] = {1};
             return b.gltf();
         },
         "bad.gltf: /nodes/1/children/0: node 0 is an ancestor of node 1: the node graph has a "
         "cycle"},
        {"required extension",
         [](GltfBuilder& b) {
             b.doc["extensionsRequired"] = {"KHR_materials_clearcoat"};
             return b.gltf();
         },
         "bad.gltf: /extensionsRequired/0: requires extension 'KHR_materials_clearcoat', "
         "which glint does not support"},
        {"truncated GLB",
         [](GltfBuilder& b) {
             const std::string glb = b.glb();
             return glb.substr(0, 60);
         },
         "bytes, the file has 60"},
        {"control bytes quoted",
         [](GltfBuilder& b) {
             b.doc["extensionsRequired"] = {"\x1b[31mred"};
             return b.gltf();
         },
         "bad.gltf: /extensionsRequired/0: requires extension '\\x1b[31mred', which glint does "
         "not support"},
        {"glTF 1.0",
         [](GltfBuilder& b) {
             b.doc["asset"]["version"] = "1.0";
             b.doc["buffers"] = json::object();
             return b.doc.dump();
         },
         "bad.gltf: /asset/version: glTF 1.0: glint reads glTF 2.0"},
        {"unknown alpha mode",
         [](GltfBuilder& b) { return with_material(b, {{"alphaMode", "CUTOUT"}}); },
         "bad.gltf: /materials/0/alphaMode: must be OPAQUE, MASK or BLEND, not 'CUTOUT'"},
        {"alpha cut-off out of range",
         [](GltfBuilder& b) {
             return with_material(b, {{"alphaMode", "MASK"}, {"alphaCutoff", 1.5}});
         },
         "bad.gltf: /materials/0/alphaCutoff: must be between 0 and 1"},
        {"emission out of range",
         [](GltfBuilder& b) { return with_material(b, {{"emissiveFactor", {0, 2, 0}}}); },
         "bad.gltf: /materials/0/emissiveFactor/1: must be between 0 and 1"},
        {"negative emissive strength",
         [](GltfBuilder& b) {
             return with_material(
                 b, {{"emissiveFactor", {1, 1, 1}},
                     {"extensions",
                      {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}}}});
         },
         "bad.gltf: /materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength: "
         "must be between 0 and 1e6"},
    };
}

TEST(Model, BadGltfInputNamesTheFileAndThePlace) {
    for (const BadGltf& c : bad_gltf()) {
        GltfBuilder b = triangle();
        const std::string bytes = c.make(b);
        try {
            parse_gltf(bytes, "bad.gltf", [](const std::string&, std::string& why) {
                why = "No such file or directory";
                return std::optional<std::string>();
            });
            ADD_FAILURE() << c.what << ": accepted";
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
                << c.what << ":\n" << e.what();
        }
    }
}

// fuzz_gltf found it (2026-12-05): the glTF 1.0 check read `asset.version` through a const
// json's [] where the asset has no version, which is undefined behaviour (a read of freed
// memory under ASan). An asset without a version is now simply not a 1.0 file.
TEST(Model, AnAssetWithoutAVersionIsReadSafely) {
    GltfBuilder b = triangle();
    b.doc["asset"] = json::object();
    try {
        const Scene scene = parse_gltf(b.gltf(), "noversion.gltf", {});
        EXPECT_EQ(scene.objects.size(), 1u);
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("noversion.gltf"), std::string::npos) << e.what();
    }
}

TEST(Model, BadModelFilesExitTwoAndWriteNothing) {
    const fs::path dir = fresh_dir();
    GltfBuilder b = triangle();
    b.node({{"children", {0}}}, false);
    b.doc["nodes"][0]["children"] = {1};
    write(dir / "cycle.gltf", b.gltf());
    write(dir / "model.fbx", "Kaydara FBX Binary");
    for (const char* file : {"cycle.gltf", "model.fbx"}) {
        const Outcome r = glint(dir, std::string("render ") + file + " -o out.png");
        EXPECT_EQ(r.exit_code, 2) << file << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << file;
        EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    }
}

TEST(Model, CameraPicksAGltfCameraAndIsRefusedElsewhere) {
    const fs::path dir = fresh_dir();
    GltfBuilder b = triangle();
    for (double y : {0.5, 0.25}) {
        b.doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", y}, {"znear", 0.1}}}});
        b.node({{"camera", b.doc["cameras"].size() - 1}, {"translation", {0, 0, 5}}});
    }
    const std::string bytes = b.gltf();
    EXPECT_NEAR(parse_gltf(bytes, "c.gltf", {}).camera.fov_y, 0.5 * 180 / M_PI, 1e-9);
    ModelOptions second;
    second.camera = 1;
    EXPECT_NEAR(parse_gltf(bytes, "c.gltf", {}, second).camera.fov_y, 0.25 * 180 / M_PI, 1e-9);
    write(dir / "c.gltf", bytes);
    Outcome r = glint(dir, "render c.gltf --camera 2 -o c.png");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("c.gltf: --camera 2: the file has 2 camera(s), 0 to 1"), std::string::npos)
        << r.err;
    r = glint(dir, "render '" GLINT_SOURCE_DIR "/scenes/default.json' --camera 0 -o c.png");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--camera picks a glTF file's camera"), std::string::npos) << r.err;
}

} // namespace
} // namespace glint
