// glTF extensions of issue 73, each on a small file made here and rendered in ray and hybrid mode
// (the same bytes in both): KHR_materials_unlit, EXT_mesh_gpu_instancing and
// KHR_mesh_quantization.
#include "gltf_scenes.h"

#include "io/error.h"
#include "trace/names.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

using namespace testing;

// KHR_materials_unlit: the colour is baseColorFactor × the base texel × COLOR_0, whatever the
// lights: a light in front and none give the same bytes, and nothing is reflected.
TEST(GltfExtensions, AnUnlitMaterialIsItsBaseColour) {
    const auto scene = [](bool lit, bool vertex_colours) {
        GltfBuilder b;
        const int base = b.texture(solid_png(255, 128, 255));
        b.doc["materials"].push_back(
            {{"pbrMetallicRoughness",
              {{"baseColorFactor", {0.2, 0.4, 0.6, 1.0}},
               {"baseColorTexture", {{"index", base}}},
               {"metallicFactor", 1.0},
               {"roughnessFactor", 0.0}}},
             {"extensions", {{"KHR_materials_unlit", json::object()}}}});
        b.doc["extensionsUsed"] = {"KHR_materials_unlit"};
        const int mesh = quad(b, 0);
        if (vertex_colours)
            b.doc["meshes"][mesh]["primitives"][0]["attributes"]["COLOR_0"] =
                b.floats({0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f},
                         "VEC3", 3);
        b.node({{"mesh", mesh}});
        camera_on_z(b);
        if (lit) light_at(b, {0, 0, 4});
        return read(b);
    };
    const Scene lit = scene(true, false);
    EXPECT_TRUE(lit.warnings.empty()) << lit.warnings.front();
    const Image image = both_modes(lit);
    const glm::ivec3 c = centre(image);
    // 0.2 × 1, 0.4 × 128/255, 0.6 × 1, as bytes.
    EXPECT_NEAR(c.x, 51, 1);
    EXPECT_NEAR(c.y, 51, 1);
    EXPECT_NEAR(c.z, 153, 1);
    EXPECT_TRUE(both_modes(scene(false, false)).rgb == image.rgb) << "a light changed an unlit surface";
    const glm::ivec3 tinted = centre(both_modes(scene(true, true)));
    EXPECT_NEAR(tinted.x, 26, 1);
    EXPECT_NEAR(tinted.y, 26, 1);
    EXPECT_NEAR(tinted.z, 77, 1);
}

// Seven instances of two meshes (EXT_mesh_gpu_instancing) under a moved and turned node: each
// instance's TRS after the node's matrix.
struct Instances {
    std::vector<float> translation = {-2, 0, 0, -1, 1, 0, 0, -1, 0.5f, 1, 0, -0.5f,
                                      2, 1, 0, 0, 0, -2, -1.5f, -1, 1};
    std::vector<float> rotation = {0, 0, 0, 1, 0, 0, 0.3826834f, 0.9238795f, 0.5f, 0.5f, 0.5f, 0.5f,
                                   0, 1, 0, 0, 0, 0, 0, 1, 0.7071068f, 0, 0, 0.7071068f, 0, 0, 0, 1};
    std::vector<float> scale = {1, 1, 1, 0.5f, 0.5f, 0.5f, 1, 2, 1, 0.7f, 0.7f, 0.7f,
                                1, 1, 1, 1.5f, 1, 0.5f, -1, 1, 1};
    json node = {{"translation", {0.3, -0.2, 0}}, {"rotation", {0, 0.2588190, 0, 0.9659258}}};

    // The two meshes' file: one node with the extension, or (`separate`) its instances written
    // as child nodes of the same node.
    std::string file(bool separate) const {
        GltfBuilder b;
        b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
        const int mesh = quad(b, 0);
        b.doc["meshes"][mesh]["primitives"].push_back(b.doc["meshes"][mesh]["primitives"][0]);
        b.doc["meshes"][mesh]["primitives"][1]["attributes"]["POSITION"] =
            b.floats({-0.5f, -0.5f, 0.3f, 0.5f, -0.5f, 0.3f, 0.5f, 0.5f, 0.6f, -0.5f, 0.5f, 0.6f}, "VEC3", 3);
        json parent = node;
        if (!separate) {
            parent["mesh"] = mesh;
            parent["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
                {"TRANSLATION", b.floats(translation, "VEC3", 3)},
                {"ROTATION", b.floats(rotation, "VEC4", 4)},
                {"SCALE", b.floats(scale, "VEC3", 3)}};
            b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
            b.node(parent);
        } else {
            json children = json::array();
            for (std::size_t i = 0; i < translation.size() / 3; ++i)
                children.push_back(b.node(
                    {{"mesh", mesh},
                     {"translation", {translation[3 * i], translation[3 * i + 1], translation[3 * i + 2]}},
                     {"rotation", {rotation[4 * i], rotation[4 * i + 1], rotation[4 * i + 2], rotation[4 * i + 3]}},
                     {"scale", {scale[3 * i], scale[3 * i + 1], scale[3 * i + 2]}}},
                    false));
            parent["children"] = children;
            b.node(parent);
        }
        b.doc["cameras"].push_back(
            {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}});
        b.node({{"camera", 0}, {"translation", {0, 0, 6}}});
        light_at(b, {2, 3, 5});
        return b.gltf();
    }
};

// The instances' hits are those of the same scene written as separate nodes: every structure,
// both modes, the same bytes; and the instances share one copy of the meshes.
TEST(GltfExtensions, InstancesHitAsTheSameSceneWrittenAsSeparateNodes) {
    const Instances instances;
    ModelOptions options;
    options.size = std::pair{48, 40};
    const Scene shared = parse_gltf(instances.file(false), "instanced.gltf", {}, options);
    const Scene separate = parse_gltf(instances.file(true), "separate.gltf", {}, options);
    ASSERT_EQ(shared.objects.size(), 14u); // 7 instances × 2 primitives
    ASSERT_EQ(separate.objects.size(), 14u);
    EXPECT_EQ(shared.meshes.size(), 2u) << "instances share their meshes";
    for (std::size_t i = 0; i < shared.objects.size(); ++i)
        EXPECT_EQ(shared.objects[i].transform, separate.objects[i].transform) << "object " << i;
    for (const AccelKind accel : {AccelKind::list, AccelKind::bvh, AccelKind::spheres,
                                  AccelKind::grid, AccelKind::kd, AccelKind::bvh2})
        for (const Mode mode : {Mode::ray, Mode::hybrid}) {
            FrameSettings settings;
            settings.mode = mode;
            const Image a = render_frame(shared, accel, settings).result.bytes();
            const Image b = render_frame(separate, accel, settings).result.bytes();
            EXPECT_TRUE(a.rgb == b.rgb) << name_of(accel) << " " << (mode == Mode::ray ? "ray" : "hybrid");
            EXPECT_GT(std::count_if(a.rgb.begin(), a.rgb.end(), [](std::uint8_t v) { return v > 0; }), 300)
                << "the instances show";
        }
}

// An instance attribute of another count than the others' is refused, naming it.
TEST(GltfExtensions, InstanceAttributesOfAnotherCountAreRefused) {
    Instances instances;
    instances.scale.resize(instances.scale.size() - 3);
    try {
        parse_gltf(instances.file(false), "instanced.gltf", {}, {});
        ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "instanced.gltf: /nodes/0/extensions/EXT_mesh_gpu_instancing/attributes/"
                      "SCALE: 6 instances, where TRANSLATION has 7"),
                  std::string::npos)
            << e.what();
    }
}

// The dome (tests/gltf_scenes.h) quantized as KHR_mesh_quantization allows: positions as SHORT
// integers k/1024 with the node scaling them by 1/1024, normals as normalized BYTE, coordinates as
// normalized UNSIGNED_SHORT.
std::string quantized_dome() {
    return dome_file(
        [](GltfBuilder& b, const Dome& d) {
            std::vector<std::int16_t> xyz;
            std::vector<std::int8_t> normal;
            std::vector<std::uint16_t> uv;
            for (const float v : d.xyz) xyz.push_back(static_cast<std::int16_t>(std::lround(v * 1024)));
            for (const float v : d.normal) normal.push_back(static_cast<std::int8_t>(std::lround(v * 127)));
            for (const float v : d.uv) uv.push_back(static_cast<std::uint16_t>(std::lround(v * 65535)));
            b.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
            b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
            return json{{"attributes", {{"POSITION", integers(b, xyz, 5122, "VEC3", 3, false)},
                                        {"NORMAL", integers(b, normal, 5120, "VEC3", 3, true)},
                                        {"TEXCOORD_0", integers(b, uv, 5123, "VEC2", 2, true)}}},
                        {"indices", b.indices(d.corners)}};
        },
        {{"mesh", 0}, {"scale", {1 / 1024.0, 1 / 1024.0, 1 / 1024.0}}});
}

// KHR_mesh_quantization: the quantized dome renders within 4 levels of its float twin. The
// positions and coordinates are the same numbers (k/1024 is exact in both; 0 and 65535/65535
// too), so the silhouette and the texels match; the normals are rounded to 1/127 a component,
// which moves a unit normal by at most √3/254 ≈ 0.007, and n·l with it: at most 0.007 × 255 ≈ 2
// levels of a fully lit diffuse term, doubled for the specular's slope.
TEST(GltfExtensions, AQuantizedMeshRendersWithinFourLevelsOfItsFloatTwin) {
    ModelOptions options;
    options.size = std::pair{48, 48};
    const Scene plain = parse_gltf(dome_file(plain_dome), "plain.gltf", {}, options);
    const Scene quantized = parse_gltf(quantized_dome(), "quantized.gltf", {}, options);
    EXPECT_TRUE(quantized.warnings.empty()) << quantized.warnings.front();
    const Image a = both_modes(plain), b = both_modes(quantized);
    const int most = largest_difference(a, b);
    EXPECT_LE(most, 4);
    EXPECT_GT(most, 0) << "the normals are rounded: some pixel should move";
}

} // namespace
} // namespace glint
