// Writes the glTF fuzzer's seeds (fuzz/gltf_fuzzer.cpp) into the directory given: small models
// made by tests/gltf_builder.h, as .gltf text and as .glb, covering what the loader reads (TRS
// and matrix nodes, instanced meshes, a camera, a light, a texture with a sampler, a strip, a
// cut-out and an emissive material, an animation with each interpolation).
#include "gltf_builder.h"
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
    return 0;
}
