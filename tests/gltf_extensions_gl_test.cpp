// glTF extensions of issue 73, each on a small file made here and rendered in ray and hybrid mode
// (the same bytes in both): KHR_materials_unlit.
#include "gltf_scenes.h"

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
        if (lit) {
            light_at(b, {0, 0, 4});
            b.doc["extensionsUsed"].push_back("KHR_lights_punctual");
        }
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

} // namespace
} // namespace glint
