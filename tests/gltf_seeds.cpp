// Writes the glTF fuzzer's seeds (fuzz/gltf_fuzzer.cpp) into the directory given: small models
// made by tests/gltf_builder.h, as .gltf text and as .glb, covering what the loader reads (TRS
// and matrix nodes, instanced meshes, a camera, a light, a texture with a sampler, a strip, a
// cut-out and an emissive material, an animation with each interpolation, a skin with morph
// targets and their weights animated, EXT_mesh_gpu_instancing, an unlit material, quantized,
// Draco and meshopt geometry, and a WebP texture).
#include "gltf_builder.h"
#include "gltf_compressed.h"
#include "gltf_models.h"
#include "rgba_png.h"

#include "io/png.h"
#include "trace/image.h"

#include <filesystem>
#include <fstream>
#include <iostream>

int main(int argc, char** argv) {
    using glint::testing::GltfBuilder;
    if (argc != 2) {
        std::cerr << "usage: gltf_seeds DIRECTORY\n";
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    GltfBuilder b;
    glint::Image image(2, 2);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(40 * i);
    const int texture = b.texture(glint::encode_png(image), {{"wrapS", 33071}, {"wrapT", 33648}});
    b.doc["materials"].push_back(
        {{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0.5}, {"roughnessFactor", 0.25}}},
         {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.5}}},
                         {"KHR_materials_ior", {{"ior", 1.4}}}}}});
    const int quad = b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, 0,
                            {0, 1, 1, 1, 1, 0, 0, 0});
    const int child = b.node({{"mesh", quad}, {"matrix", {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1}}},
                             false);
    b.node({{"mesh", quad}, {"translation", {0, 0, -1}}, {"rotation", {0, 0.6, 0, 0.8}},
            {"scale", {1, 2, 1}}, {"children", {child}}});
    b.doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {0, 0, 6}}});
    b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior"};
    b.doc["extensions"] = {{"KHR_lights_punctual",
                            {{"lights", {{{"type", "point"}, {"color", {1, 0.9, 0.8}}, {"intensity", 0.8}}}}}}};
    b.node({{"translation", {2, 3, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    std::ofstream(dir / "scene.gltf", std::ios::binary) << b.gltf();
    std::ofstream(dir / "scene.glb", std::ios::binary) << b.glb();
    GltfBuilder strip;
    strip.node({{"mesh", strip.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {0, 1, 2, 3})}});
    strip.doc["meshes"][0]["primitives"][0]["mode"] = 5;
    std::ofstream(dir / "strip.gltf", std::ios::binary) << strip.gltf();
    // A cut-out and an emissive material, and an animation with each interpolation.
    GltfBuilder moving;
    const int leaf = moving.texture(glint::testing::rgba_png(2, 1, {255, 255, 255, 0, 255, 255, 255, 255}));
    moving.doc["materials"].push_back(
        {{"alphaMode", "MASK"}, {"alphaCutoff", 0.4},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", leaf}}}}}});
    moving.doc["materials"].push_back(
        {{"emissiveFactor", {1, 0.5, 0}}, {"emissiveTexture", {{"index", leaf}}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3}}}}}});
    const int card = moving.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, 0,
                                 {0, 1, 1, 1, 1, 0, 0, 0});
    const int lamp = moving.mesh({0, 0, -1, 1, 0, -1, 0, 1, -1}, {0, 1, 2}, 1, {0, 0, 1, 0, 0, 1});
    moving.node({{"mesh", card}});
    moving.node({{"mesh", lamp}, {"rotation", {0, 0, 0, 1}}});
    const int times = moving.floats({0, 0.5, 1}, "SCALAR", 1);
    moving.doc["animations"] = {
        {{"samplers",
          {{{"input", times}, {"output", moving.floats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3)}},
           {{"input", times},
            {"output", moving.floats({0, 0, 0, 1, 0, 0.6f, 0, 0.8f, 0, 1, 0, 0}, "VEC4", 4)},
            {"interpolation", "STEP"}},
           {{"input", times},
            {"output", moving.floats({0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0, 0, 0, 0,
                                      1, 1, 1, 0, 0, 0},
                                     "VEC3", 3)},
            {"interpolation", "CUBICSPLINE"}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
           {{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}},
           {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}}}}}};
    std::ofstream(dir / "moving.gltf", std::ios::binary) << moving.gltf();
    std::ofstream(dir / "moving.glb", std::ios::binary) << moving.glb();
    // DESIGN §14: metallic-roughness and occlusion textures read per texel, a texture through
    // TEXCOORD_1 with its transform, one-sided faces under a negative scale, an emissive texture
    // through a set the mesh has.
    GltfBuilder texels;
    const int maps = texels.texture(glint::encode_png(image));
    nlohmann::json on_second = {{"index", maps}, {"texCoord", 1}};
    on_second["extensions"]["KHR_texture_transform"] = {{"offset", {0.5, 0}}, {"texCoord", 1}};
    texels.doc["materials"].push_back(
        {{"pbrMetallicRoughness",
          {{"baseColorTexture", on_second}, {"metallicRoughnessTexture", {{"index", maps}}}}},
         {"occlusionTexture", {{"index", maps}, {"strength", 0.5}}},
         {"emissiveFactor", {0.2, 0.2, 0.2}},
         {"emissiveTexture", {{"index", maps}, {"texCoord", 1}}},
         {"doubleSided", false}});
    const int panel = texels.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, 0,
                                  {0, 1, 1, 1, 1, 0, 0, 0});
    texels.doc["meshes"][panel]["primitives"][0]["attributes"]["TEXCOORD_1"] =
        texels.floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2", 2);
    texels.node({{"mesh", panel}});
    texels.node({{"mesh", panel}, {"scale", {-1, 1, 1}}, {"translation", {2.5, 0, 0}}});
    texels.doc["extensionsUsed"] = {"KHR_texture_transform"};
    std::ofstream(dir / "texels.gltf", std::ios::binary) << texels.gltf();
    std::ofstream(dir / "texels.glb", std::ios::binary) << texels.glb();
    // DESIGN §14's skins and morph targets: a quad skinned to two joints, with two morph
    // targets, the second joint's rotation and the weights animated; drawn by an instancing node
    // too (its instances each place the node's mesh), under an unlit material.
    using glint::testing::integers;
    GltfBuilder skin;
    const nlohmann::json quad_attributes = {
        {"POSITION", skin.floats({-1, 0, 0, 1, 0, 0, 1, 2, 0, -1, 2, 0}, "VEC3", 3)},
        {"NORMAL", skin.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3)},
        {"JOINTS_0", integers<std::uint16_t>(skin, {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, 5123, "VEC4", 4, false)},
        {"WEIGHTS_0", skin.floats({1, 0, 0, 0, 0.7f, 0.3f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4)}};
    skin.doc["materials"].push_back({{"extensions", {{"KHR_materials_unlit", nlohmann::json::object()}}}});
    skin.doc["meshes"].push_back(
        {{"primitives",
          {{{"attributes", quad_attributes},
            {"indices", skin.indices({0, 1, 2, 0, 2, 3})},
            {"material", 0},
            {"targets", {{{"POSITION", skin.floats({0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3)}},
                         {{"POSITION", skin.floats({0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0}, "VEC3", 3)},
                          {"NORMAL", skin.floats({0, 0.1f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3)}}}}}}},
         {"weights", {0.5, 0}}});
    const int hip = skin.node({{"name", "hip"}});
    const int knee = skin.node({{"translation", {0, 1, 0}}}, false);
    skin.doc["nodes"][hip]["children"] = {knee};
    skin.doc["skins"] = {{{"joints", {hip, knee}},
                          {"inverseBindMatrices",
                           skin.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
                                       "MAT4", 16)}}};
    skin.node({{"mesh", 0}, {"skin", 0}});
    skin.node({{"mesh", 0},
               {"translation", {3, 0, 0}},
               {"extensions",
                {{"EXT_mesh_gpu_instancing",
                  {{"attributes",
                    {{"TRANSLATION", skin.floats({0, 0, 0, 2, 0, 0, 0, 2, 0}, "VEC3", 3)},
                     {"SCALE", skin.floats({1, 1, 1, 0.5f, 0.5f, 0.5f, 1, 2, 1}, "VEC3", 3)}}}}}}}});
    const int key_times = skin.floats({0, 1}, "SCALAR", 1);
    skin.doc["animations"] = {
        {{"samplers",
          {{{"input", key_times}, {"output", skin.floats({0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f}, "VEC4", 4)}},
           {{"input", key_times}, {"output", skin.floats({0, 0, 1, 0.5f}, "SCALAR", 1)}}}},
         {"channels",
          {{{"sampler", 0}, {"target", {{"node", knee}, {"path", "rotation"}}}},
           {{"sampler", 1}, {"target", {{"node", 2}, {"path", "weights"}}}}}}}};
    skin.doc["extensionsUsed"] = {"KHR_materials_unlit", "EXT_mesh_gpu_instancing"};
    std::ofstream(dir / "skin.gltf", std::ios::binary) << skin.gltf();
    std::ofstream(dir / "skin.glb", std::ios::binary) << skin.glb();
    // Compressed and quantized geometry and a WebP texture (tests/gltf_compressed.h).
    using glint::testing::dome_file;
    std::ofstream(dir / "quantized.gltf", std::ios::binary) << dome_file([](GltfBuilder& q, const glint::testing::Dome& d) {
        std::vector<std::int16_t> xyz;
        for (const float v : d.xyz) xyz.push_back(static_cast<std::int16_t>(v * 1024));
        q.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
        return nlohmann::json{{"attributes", {{"POSITION", integers(q, xyz, 5122, "VEC3", 3, false)}}},
                              {"indices", q.indices(d.corners)}};
    }, {{"mesh", 0}, {"scale", {1 / 1024.0, 1 / 1024.0, 1 / 1024.0}}});
    const glint::testing::DracoDome draco = glint::testing::encode_dome();
    std::ofstream(dir / "draco.gltf", std::ios::binary) << glint::testing::draco_dome(draco);
    std::ofstream(dir / "draco.glb", std::ios::binary) << glint::testing::draco_dome(draco, true);
    std::ofstream(dir / "meshopt.gltf", std::ios::binary) << glint::testing::meshopt_dome();
    std::ofstream(dir / "meshopt.glb", std::ios::binary) << glint::testing::meshopt_dome(false, true);
    std::ofstream(dir / "webp.gltf", std::ios::binary) << glint::testing::webp_quad(true).gltf();
    return 0;
}
