// glTF materials per texel, one-sided faces, unusable textures, the key light and environments
// (DESIGN §14, issue 72's items 1–7), each on a small file made here, rendered in ray and hybrid
// mode: what each mode shows, and the same bytes in both (hybrid = ray, with culling and with an
// environment).
#include "gltf_scenes.h"

#include "trace/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

using json = nlohmann::json;
using namespace testing;

// Item 1: metallicFactor left at 1 and the metallic-roughness texture saying "no metal" (blue
// 0): the base colour texel shows as a diffuse colour; with blue 255 the surface is a metal whose
// specular colour is the texel's (no longer the factor's grey).
TEST(GltfMaterials, TheMetallicRoughnessTextureKeepsTheBaseColour) {
    for (const std::uint8_t blue : {0, 255}) {
        GltfBuilder b;
        const int base = b.texture(solid_png(192, 134, 57));
        const int metal_rough = b.texture(solid_png(0, 255, blue));
        b.doc["materials"].push_back({{"pbrMetallicRoughness",
                                       {{"baseColorTexture", {{"index", base}}},
                                        {"metallicRoughnessTexture", {{"index", metal_rough}}}}}});
        b.node({{"mesh", quad(b, 0)}});
        camera_on_z(b);
        light_at(b, {0, 0, 4});
        const Scene scene = read(b);
        const Image image = both_modes(scene);
        const glm::ivec3 c = centre(image);
        if (blue == 0) { // a dielectric: k_d = the texel
            EXPECT_GT(c.x, 150) << c.x << " " << c.y << " " << c.z;
            EXPECT_GT(c.x, c.y + 40);
            EXPECT_GT(c.y, c.z + 40);
        } else { // a rough metal (green 255: roughness 1, no reflection): k_s = the texel
            EXPECT_GT(c.x, c.z) << c.x << " " << c.y << " " << c.z;
        }
    }
}

// Item 1, the rest of DESIGN §14's formula: occlusion's red scales the ambient term, and the
// Phong inputs with every texel 1 are the factors' (what the preview draws).
TEST(GltfMaterials, OcclusionScalesTheAmbientTerm) {
    GltfBuilder b;
    const int dark = b.texture(solid_png(0, 0, 0));
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
                                  {"occlusionTexture", {{"index", dark}, {"strength", 1.0}}}});
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
    b.node({{"mesh", quad(b, 0)}, {"translation", {-1.1, 0, 0}}});
    b.node({{"mesh", quad(b, 1)}, {"translation", {1.1, 0, 0}}});
    camera_on_z(b);
    Scene scene = read(b); // no lights in the file: the default ones and ambient 0.1
    scene.lights.clear();  // ambient alone
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_NEAR(scene.materials[2].diffuse.x, 1.0f, 1e-6f);
    EXPECT_NEAR(scene.materials[2].ambient.x, 1.04f, 1e-6f); // k_d + k_s(1 − 0), k_s = 0.04
    const Image image = both_modes(scene);
    EXPECT_EQ(image.pixel(4, 12)[0], 0);   // occluded: no ambient
    EXPECT_GT(image.pixel(19, 12)[0], 20); // 0.1 × 1.04 ≈ 27
}

// Item 2: doubleSided false culls a triangle seen from behind in both modes; a negative scale
// flips the winding, so the mirrored quad facing the camera stays; doubleSided true shows both.
TEST(GltfMaterials, OneSidedFacesAreCulledAndANegativeScaleFlipsTheWinding) {
    struct Case {
        bool reversed, double_sided, mirrored, seen;
    };
    for (const Case c : {Case{false, false, false, true}, Case{true, false, false, false},
                         Case{true, true, false, true}, Case{false, false, true, true},
                         Case{true, false, true, false}}) {
        GltfBuilder b;
        b.doc["materials"].push_back(
            {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}, {"doubleSided", c.double_sided}});
        json node = {{"mesh", quad(b, 0, c.reversed)}};
        // Mirrored in x: the placed normal still faces +z, the window's winding turns.
        if (c.mirrored) node["scale"] = {-1, 1, 1};
        b.node(node);
        camera_on_z(b);
        light_at(b, {0, 0, 4});
        const Image image = both_modes(read(b));
        EXPECT_EQ(centre(image).x > 0, c.seen) << "reversed " << c.reversed << ", doubleSided "
                                               << c.double_sided << ", mirrored " << c.mirrored;
    }
}

// Item 2, shadow rays: a one-sided occluder between a floor and the light shadows the floor only
// when the shadow ray meets its front.
TEST(GltfMaterials, OneSidedFacesCastShadowsFromTheirFrontOnly) {
    for (const bool facing_floor : {true, false}) {
        GltfBuilder b;
        b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
        b.node({{"mesh", quad(b, 0)}, {"scale", {3, 3, 1}}}); // the floor, facing the camera
        // The occluder, small, between the floor and the light, its front towards the floor
        // (−z: reversed) or away from it.
        b.node({{"mesh", quad(b, 0, facing_floor)},
                {"translation", {0, 0, 1}},
                {"scale", {0.5, 0.5, 1}}});
        camera_on_z(b);
        light_at(b, {0, 0, 2});
        const Image image = both_modes(read(b));
        // A floor pixel beside the occluder, in its shadow or not.
        const std::uint8_t lit = image.pixel(12 + 6, 12)[0];
        if (facing_floor)
            EXPECT_EQ(lit, 0) << "the occluder's front faces the floor: it shadows it";
        else
            EXPECT_GT(lit, 0) << "the occluder's back faces the floor: light passes";
    }
}

// Items 3 and 7: an emissive texture that cannot be read leaves no emission, with a warning
// naming the image and the whole reason (a long path, and a name beyond ASCII); one read through
// a set the mesh lacks leaves none either, and one through TEXCOORD_2 is not used.
TEST(GltfMaterials, AnEmissiveTextureThatCannotBeUsedLeavesNoEmission) {
    const std::string far_away = "textures/" + std::string(120, 'd') + "/glühend.png";
    for (const int case_ : {0, 1, 2}) {
        GltfBuilder b;
        int texture = 0;
        if (case_ == 0) {
            b.doc["images"].push_back({{"uri", far_away}});
            b.doc["textures"].push_back({{"source", 0}});
        } else {
            texture = b.texture(solid_png(255, 255, 255));
        }
        b.doc["materials"].push_back(
            {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0.0}}},
             {"emissiveFactor", {1, 1, 1}},
             {"emissiveTexture", {{"index", texture}, {"texCoord", case_ == 2 ? 2 : case_}}}});
        b.node({{"mesh", quad(b, 0)}});
        camera_on_z(b);
        const ModelFiles missing = [](const std::string&, std::string& why) {
            why = "no such file";
            return std::optional<std::string>();
        };
        Scene scene = read(b, "glow.gltf", missing);
        scene.lights.clear(), scene.ambient = glm::vec3(0.0f); // emission alone
        const Image image = both_modes(scene);
        EXPECT_EQ(centre(image), glm::ivec3(0)) << "case " << case_;
        if (case_ == 1) continue; // readable; only this mesh lacks TEXCOORD_1
        ASSERT_FALSE(scene.warnings.empty()) << "case " << case_;
        const std::string& warning = scene.warnings.front();
        if (case_ == 0) {
            EXPECT_NE(warning.find("glow.gltf: /images/0: texture not used"), std::string::npos)
                << warning;
            EXPECT_NE(warning.find(std::string(120, 'd') + "/gl\\xc3\\xbchend.png"),
                      std::string::npos)
                << warning;
            EXPECT_NE(warning.find("no such file"), std::string::npos) << warning;
        } else {
            EXPECT_NE(warning.find("/materials/0/emissiveTexture"), std::string::npos) << warning;
            EXPECT_NE(warning.find("TEXCOORD_2"), std::string::npos) << warning;
        }
    }
}

// Item 5: a base colour texture with texCoord 1 reads TEXCOORD_1.
TEST(GltfMaterials, TexCoordOneReadsTheSecondSet) {
    GltfBuilder b;
    // Left half red, right half blue; TEXCOORD_0 maps the quad into the red half, TEXCOORD_1
    // into the blue one.
    Image two(2, 1);
    two.pixel(0, 0)[0] = 255, two.pixel(1, 0)[2] = 255;
    const int texture = b.texture(encode_png(two), {{"magFilter", 9728}, {"wrapS", 33071}});
    b.doc["materials"].push_back(
        {{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", texture}, {"texCoord", 1}}}, {"metallicFactor", 0.0}}}});
    const int mesh = quad(b, 0, false, {0.8f, 0.5f, 0.8f, 0.5f, 0.8f, 0.5f, 0.8f, 0.5f});
    b.doc["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        b.floats({0.2f, 0.5f, 0.2f, 0.5f, 0.2f, 0.5f, 0.2f, 0.5f}, "VEC2", 2);
    b.node({{"mesh", mesh}});
    camera_on_z(b);
    light_at(b, {0, 0, 4});
    const Scene scene = read(b);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const glm::ivec3 c = centre(both_modes(scene));
    // Blue, with the white highlight of k_s = 0.04 in every channel.
    EXPECT_GT(c.z, 100) << c.x << " " << c.y << " " << c.z;
    EXPECT_EQ(c.x, c.y);
}

// Item 4: with a file camera far from the model and no lights in the file, the key light stands
// off the model's centre at √2 times the camera's distance, above and to the left: not on the
// eye.
TEST(GltfMaterials, TheKeyLightIsPlacedFromTheModelsCentre) {
    GltfBuilder b;
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
    b.node({{"mesh", quad(b, 0)}, {"translation", {3, 0, 0}}});
    b.doc["cameras"].push_back(
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.1}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {3, 0, 40}}});
    const Scene scene = read(b);
    ASSERT_EQ(scene.lights.size(), 2u);
    const DVec3 centre(3, 0, 0), eye(3, 0, 40);
    const DVec3 key = scene.lights[0].position;
    EXPECT_NEAR(glm::length(key - centre), std::sqrt(2.0) * 40, 1e-9);
    EXPECT_NEAR(key.y - centre.y, 0.8 * 40, 1e-9);  // up
    EXPECT_NEAR(key.x - centre.x, -0.6 * 40, 1e-9); // left
    EXPECT_EQ(scene.lights[1].position, eye);       // the fill light at the eye
}

// Item 6: an environment's orientation is DESIGN §14's formula, texel by texel; camera and
// reflected rays see it in both modes, and the item buffer's empty pixels resolve to it.
TEST(GltfMaterials, TheEnvironmentFollowsTheFormulaAndIsSeenInBothModes) {
    auto environment = std::make_shared<Environment>();
    environment->width = 4, environment->height = 2;
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k) environment->rgb.push_back(static_cast<float>(i * 3 + k) / 24);
    environment->brightest = glm::vec3(21, 22, 23) / 24.0f; // as reading one sets it
    const auto texel = [&](int x, int y) {
        const float* p = &environment->rgb[static_cast<std::size_t>(y * 4 + x) * 3];
        return glm::vec3(p[0], p[1], p[2]);
    };
    // Texel (i, j)'s centre: u = (i + ½)/4, v = (j + ½)/2, so φ = 2π(u − ½), θ = πv, and
    // d = (sin θ sin φ, cos θ, −sin θ cos φ).
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) {
            const double phi = 2 * std::numbers::pi * ((i + 0.5) / 4 - 0.5);
            const double theta = std::numbers::pi * (j + 0.5) / 2;
            const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                               -std::sin(theta) * std::cos(phi));
            const glm::vec3 got = environment_radiance(*environment, d);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], texel(i, j)[k], 1e-5) << i << j;
        }
    // Straight ahead of a camera on +z (−z): u = ½, between texels 1 and 2 of the band v = ½.
    const glm::vec3 ahead = environment_radiance(*environment, {0, 0, -1});
    EXPECT_NEAR(ahead.x, (texel(1, 0).x + texel(2, 0).x + texel(1, 1).x + texel(2, 1).x) / 4, 1e-5);

    // A smooth metal quad filling part of the view: beside it the camera sees the environment,
    // on it the reflection of what lies behind the camera (+z: u = 0 and 1, wrapped).
    GltfBuilder b;
    b.doc["materials"].push_back(
        {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}});
    b.node({{"mesh", quad(b, 0)}, {"scale", {0.5, 0.5, 1}}});
    camera_on_z(b);
    Scene scene = read(b);
    scene.lights.clear(), scene.ambient = glm::vec3(0.0f);
    scene.environment = environment;
    const Image with = both_modes(scene);
    scene.environment = nullptr;
    const Image without = both_modes(scene);
    EXPECT_EQ(centre(without), glm::ivec3(0)); // a metal with nothing to reflect is black
    EXPECT_GT(centre(with).x + centre(with).y + centre(with).z, 0);
    EXPECT_GT(with.pixel(0, 12)[2], 0); // the edge of the view: the environment itself
    EXPECT_EQ(without.pixel(0, 12)[2], 0);
}

} // namespace
} // namespace glint
