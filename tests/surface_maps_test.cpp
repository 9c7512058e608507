// What a model's surface carries besides its base colour (docs/SCENES.md, "Normal maps, vertex
// colours and texture transforms"): a normal map tilts the shading normal towards its texel in
// the tangent frame, vertex colours multiply the base colour, and KHR_texture_transform maps the
// texture coordinates before every lookup; the glTF loader reads each.
#include "gltf_builder.h"

#include "io/gltf_loader.h"
#include "io/png.h"
#include "trace/image.h"
#include "trace/render.h"
#include "trace/texture.h"
#include "trace/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glint {
namespace {

using testing::GltfBuilder;

std::shared_ptr<TextureImage> solid(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    auto image = std::make_shared<TextureImage>();
    image->name = "solid";
    image->width = image->height = 1;
    image->rgb = {r, g, b};
    return image;
}

// A unit quad in the plane z = 0 facing +z (u along +x, v down the image: along −y), seen from
// z = 4, with a normal map of one texel.
Scene mapped_quad(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    Scene scene;
    scene.camera.eye = {0, 0, 4};
    scene.camera.width = scene.camera.height = 16;
    scene.lights.push_back({{0, 0, 10}, {1, 1, 1}});
    scene.materials.resize(1);
    scene.materials[0].normal_texture = 0;
    scene.textures.push_back({solid(r, g, b)});
    TriangleMesh quad;
    quad.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(quad);
    SceneObject o;
    o.shape = ShapeKind::mesh;
    scene.objects.push_back(o);
    return scene;
}

Vec3 shading_normal(const Scene& scene) {
    const World world(scene);
    const Ray ray{Vec3(0), Vec3(0.1f, 0.05f, -1)};
    const Hit hit = world.intersect(ray);
    EXPECT_TRUE(hit.found());
    return world.surface(ray, hit).shading;
}

TEST(SurfaceMaps, ANormalMapTiltsTheShadingNormalInTheTangentFrame) {
    // Texel (255, 128, 255): x = 1, y ≈ 0, z = 1 in tangent space: halfway towards +u (+x).
    const Vec3 n = shading_normal(mapped_quad(255, 128, 255));
    EXPECT_NEAR(n.x, std::sqrt(0.5), 1e-2);
    EXPECT_NEAR(n.z, std::sqrt(0.5), 1e-2);
    // y: the bitangent points up the image (decreasing v, +y here).
    const Vec3 up = shading_normal(mapped_quad(128, 255, 255));
    EXPECT_NEAR(up.y, std::sqrt(0.5), 1e-2);
    // A flat texel leaves the normal as it was (up to the byte's half step).
    EXPECT_NEAR(shading_normal(mapped_quad(128, 128, 255)).z, 1, 1e-3);
    // The scale multiplies x and y; a given tangent replaces the computed one.
    Scene scaled = mapped_quad(255, 128, 255);
    scaled.materials[0].normal_scale = 0;
    EXPECT_NEAR(shading_normal(scaled).z, 1, 1e-3);
    Scene given = mapped_quad(255, 128, 255);
    given.meshes[0].tangents.assign(4, glm::vec4(-1, 0, 0, 1));
    EXPECT_NEAR(shading_normal(given).x, -std::sqrt(0.5), 1e-2);
    // The tilt is in the image: the lit quad's brightness changes.
    EXPECT_NE(render(World(mapped_quad(255, 128, 255))).bytes().rgb,
              render(World(mapped_quad(128, 128, 255))).bytes().rgb);
}

TEST(SurfaceMaps, VertexColoursMultiplyTheBaseColour) {
    Scene scene = mapped_quad(128, 128, 255);
    scene.materials[0].normal_texture = kNoTexture;
    scene.meshes[0].colours.assign(4, glm::vec3(1, 0, 0));
    const Image image = render(World(scene)).bytes();
    const std::uint8_t* centre = image.pixel(8, 8);
    EXPECT_GT(centre[0], 100);
    EXPECT_EQ(centre[1], 0);
    EXPECT_EQ(centre[2], 0);
}

TEST(SurfaceMaps, ATextureTransformMapsTheCoordinatesFirst) {
    auto image = std::make_shared<TextureImage>();
    image->width = 2, image->height = 1;
    image->rgb = {255, 0, 0, 0, 0, 255};
    Texture plain{image, Wrap::repeat, Wrap::repeat};
    Texture shifted = plain;
    shifted.uv_transform[2] = glm::vec3(0.5f, 0, 1); // offset (0.5, 0)
    EXPECT_EQ(sample_texture(shifted, {0.25f, 0.5f}).colour,
              sample_texture(plain, {0.75f, 0.5f}).colour);
    EXPECT_EQ(sample_alpha(shifted, {0.25f, 0.5f}), 1.0f);
}

// glTF: COLOR_0, TANGENT, normalTexture with its scale, and KHR_texture_transform (offset,
// rotation, scale: uv' = T · R · S · uv as the extension writes it) are read.
TEST(SurfaceMaps, TheGltfLoaderReadsThem) {
    GltfBuilder b;
    Image texel(1, 1);
    const int map = b.texture(encode_png(texel));
    const nlohmann::json transform = {
        {"offset", {0.5, 0.25}}, {"rotation", std::numbers::pi / 2}, {"scale", {2, 3}}};
    nlohmann::json normal = {{"index", map}, {"scale", 0.5}};
    normal["extensions"]["KHR_texture_transform"] = transform;
    b.doc["materials"].push_back({{"normalTexture", normal}});
    const int mesh = b.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, 0, {0, 0, 1, 0, 0, 1});
    auto& attributes = b.doc["meshes"][mesh]["primitives"][0]["attributes"];
    attributes["COLOR_0"] = b.floats({1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1}, "VEC4", 4);
    attributes["TANGENT"] = b.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, -1}, "VEC4", 4);
    b.node({{"mesh", mesh}});
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    const Scene scene = parse_gltf(b.gltf(), "maps.gltf", {});
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const Material& m = scene.materials.at(1);
    ASSERT_NE(m.normal_texture, kNoTexture);
    EXPECT_EQ(m.normal_scale, 0.5f);
    const TriangleMesh& t = scene.meshes.at(0);
    EXPECT_EQ(t.colours.at(1), glm::vec3(0, 1, 0));
    EXPECT_EQ(t.tangents.at(2), glm::vec4(1, 0, 0, -1));
    // (1, 0) scaled to (2, 0), turned a quarter (the extension's rotation: to (0, −2)), offset.
    const glm::vec3 uv = scene.textures.at(m.normal_texture).uv_transform * glm::vec3(1, 0, 1);
    EXPECT_NEAR(uv.x, 0.5, 1e-6);
    EXPECT_NEAR(uv.y, 0.25 - 2, 1e-6);
}

// --colour srgb's two curves: the encoding of 0, 1 and a mid grey (0.5 linear is byte 188), and
// decoding a byte then encoding it again returns it; a colour texture marked sRGB is decoded
// before filtering.
TEST(SurfaceMaps, TheSrgbCurvesAreInversesAndTexturesDecodeBeforeFiltering) {
    EXPECT_EQ(to_srgb_byte(0.0f), 0);
    EXPECT_EQ(to_srgb_byte(1.0f), 255);
    EXPECT_EQ(to_srgb_byte(0.5f), 188);
    EXPECT_EQ(to_srgb_byte(std::nanf("")), 0);
    for (int b = 0; b < 256; ++b) EXPECT_EQ(to_srgb_byte(srgb_to_linear(std::uint8_t(b))), b) << b;
    auto image = std::make_shared<TextureImage>();
    image->width = 2, image->height = 1;
    image->rgb = {0, 0, 0, 188, 188, 188};
    Texture t{image, Wrap::clamp, Wrap::clamp};
    t.srgb = true;
    EXPECT_NEAR(sample_texture(t, {0.75f, 0.5f}).colour.x, 0.5f, 3e-3);
    // Halfway between the texels: the mean of the decoded values, not the decoded mean.
    EXPECT_NEAR(sample_texture(t, {0.5f, 0.5f}).colour.x, 0.5f * srgb_to_linear(188), 1e-6);
}

} // namespace
} // namespace glint
