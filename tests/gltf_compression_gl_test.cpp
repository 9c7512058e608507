// Compressed glTF geometry and textures of issue 73, each made here with the same library's
// encoder and rendered in ray and hybrid mode (the same bytes in both) against its plain twin:
// KHR_draco_mesh_compression, EXT_meshopt_compression and EXT_texture_webp; and buffers that do
// not decode, refused naming the place.
#include "gltf_compressed.h"
#include "gltf_scenes.h"

#include "io/error.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

using namespace testing;

// KHR_draco_mesh_compression: the Draco dome renders within 4 levels of its plain twin. The
// positions are encoded as floats (the silhouette is the same); the coordinates are 0 or 1 over
// a one-colour texture; the normals are quantized to 10 bits an octahedral coordinate, closer than
// KHR_mesh_quantization's normalized bytes, so the same bound holds (tests/gltf_extensions_gl_test.cpp).
TEST(GltfCompression, ADracoMeshRendersWithinFourLevelsOfItsPlainTwin) {
    ModelOptions options;
    options.size = std::pair{48, 48};
    const Scene plain = parse_gltf(dome_file(plain_dome), "plain.gltf", {}, options);
    const DracoDome encoded = encode_dome();
    const Image twin = both_modes(plain);
    for (const bool glb : {false, true}) {
        const Scene draco = parse_gltf(draco_dome(encoded, glb), glb ? "draco.glb" : "draco.gltf", {}, options);
        EXPECT_TRUE(draco.warnings.empty()) << draco.warnings.front();
        ASSERT_EQ(draco.meshes.size(), 1u);
        EXPECT_EQ(draco.meshes[0].triangles.size(), 128u);
        EXPECT_LE(largest_difference(twin, both_modes(draco)), 4) << (glb ? "GLB" : "glTF");
    }
}

// Bytes that are not Draco's are refused, naming the primitive's extension.
TEST(GltfCompression, ADracoBufferThatDoesNotDecodeIsRefused) {
    DracoDome encoded = encode_dome();
    for (std::size_t i = 0; i < encoded.bytes.size(); ++i) encoded.bytes[i] = static_cast<char>(0x5a ^ i);
    try {
        parse_gltf(draco_dome(encoded), "draco.gltf", {}, {});
        ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("draco.gltf: /meshes/0/primitives/0/extensions/"
                                             "KHR_draco_mesh_compression: the Draco data does not "
                                             "decode"),
                  std::string::npos)
            << e.what();
    }
}

// EXT_meshopt_compression: the meshopt dome renders within 4 levels of its plain twin. The
// vertex and index codecs are lossless; the octahedral filter keeps 8 bits a normal component,
// as KHR_mesh_quantization's normalized bytes do, so the same bound holds.
TEST(GltfCompression, AMeshoptMeshRendersWithinFourLevelsOfItsPlainTwin) {
    ModelOptions options;
    options.size = std::pair{48, 48};
    const Scene plain = parse_gltf(dome_file(plain_dome), "plain.gltf", {}, options);
    const Image twin = both_modes(plain);
    for (const bool glb : {false, true}) {
        const Scene packed =
            parse_gltf(meshopt_dome(false, glb), glb ? "meshopt.glb" : "meshopt.gltf", {}, options);
        EXPECT_TRUE(packed.warnings.empty()) << packed.warnings.front();
        ASSERT_EQ(packed.meshes.size(), 1u);
        EXPECT_EQ(packed.meshes[0].vertices, plain.meshes[0].vertices) << "positions are lossless";
        EXPECT_LE(largest_difference(twin, both_modes(packed)), 4) << (glb ? "GLB" : "glTF");
    }
    try {
        parse_gltf(meshopt_dome(true), "meshopt.gltf", {}, options);
        ADD_FAILURE() << "damaged bytes accepted";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("/extensions/EXT_meshopt_compression: the meshopt "
                                             "data does not decode"),
                  std::string::npos)
            << e.what();
    }
}

// EXT_texture_webp: a lossless WebP texture renders the same bytes as the same pixels as a PNG.
TEST(GltfCompression, AWebpTextureRendersAsTheSamePixelsInAPng) {
    const Scene webp = read(webp_quad(true), "webp.gltf");
    EXPECT_TRUE(webp.warnings.empty()) << webp.warnings.front();
    ASSERT_EQ(webp.textures.size(), 1u);
    EXPECT_EQ(webp.textures[0].image->rgb, checker_pixels());
    EXPECT_TRUE(both_modes(webp).rgb == both_modes(read(webp_quad(false), "png.gltf")).rgb);
}

} // namespace
} // namespace glint
