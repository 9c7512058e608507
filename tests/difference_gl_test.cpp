// Hybrid sides compared (frame/difference.h): what the item buffer alone changes is the primary
// hit, so a trusted coarse item buffer against ray mode differs by `primary` only, and
// `explain --against` names the cause the map shows with hybrid sides too (their trees come from
// the frame's own item buffer). Ray-mode sides: difference_test.cpp.
#include "difference_shared.h"
#include "frame/difference_maps.h"
#include "frame/explain_against.h"
#include "io/load_scene.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

constexpr const char* kShipped[] = {"default",    "mirrors",   "transforms", "shadows",
                                    "primitives", "instances", "whitted",    "glass"};

Side side_of(const Scene& scene, Mode mode) {
    Side side;
    side.scene = scene;
    side.frame.mode = mode;
    return side;
}

// The trusted coarse item buffer: tessellation 4, every object as a mesh, its word taken.
Side trusted_coarse(const Scene& scene) {
    Side side = side_of(scene, Mode::hybrid);
    side.frame.raster = RasterMode::mesh;
    side.frame.tessellation = 4;
    side.frame.resolve = Resolve::trust;
    return side;
}

// Balls in front of balls: where a 4-segment outline falls inside the sphere in front, the item
// buffer names the one behind, and trust takes its word. Nothing else differs: both sides hit
// the same object exactly wherever the ids agree, so every differing pixel is `primary`.
TEST(DifferenceHybrid, ATrustedCoarseItemBufferDiffersByPrimaryHitsOnly) {
    Scene scene = load_scene(GLINT_SOURCE_DIR "/scenes/spd/balls-2.nff");
    scene.camera.width = scene.camera.height = 200;
    scene.render.samples = 1;
    const RenderedSide a(trusted_coarse(scene)), b(side_of(scene, Mode::ray));
    const FrameDifference d = difference(a, b, false);
    EXPECT_GT(d.differing, 10u);
    EXPECT_EQ(d.tallies[static_cast<std::size_t>(Cause::primary)].pixels, d.differing);
}

TEST(DifferenceHybrid, HybridAgainstItselfDiffersNowhere) {
    for (const char* name : kShipped) {
        Scene scene = load_scene(std::string(GLINT_SOURCE_DIR "/scenes/") + name + ".json");
        scene.camera.width = 64, scene.camera.height = 48;
        const RenderedSide a(trusted_coarse(scene)), b(trusted_coarse(scene));
        EXPECT_EQ(difference(a, b, true).differing, 0u) << name;
    }
}

// 200 pixels of each shipped scene, the differing ones first: hybrid (trusted, coarse) against
// ray, and hybrid as it renders by default against the exact image.
TEST(DifferenceHybrid, ExplainAgainstAgreesWithTheCauseMap) {
    for (const char* name : kShipped) {
        Scene scene = load_scene(std::string(GLINT_SOURCE_DIR "/scenes/") + name + ".json");
        scene.camera.width = 64, scene.camera.height = 48;
        Side exact = side_of(scene, Mode::ray);
        make_exact(exact);
        const std::pair<Side, Side> pairs[] = {
            {trusted_coarse(scene), side_of(scene, Mode::ray)},
            {side_of(scene, Mode::hybrid), exact},
        };
        for (const auto& [side_a, side_b] : pairs) {
            const RenderedSide a(side_a), b(side_b);
            const FrameDifference d = difference(a, b, false);
            const std::vector<std::uint32_t> pixels = testing::pixels_to_check(d);
            const auto ta = a.trees(pixels), tb = b.trees(pixels);
            for (std::size_t i = 0; i < pixels.size(); ++i) {
                const int x = static_cast<int>(pixels[i] % 64),
                          y = static_cast<int>(pixels[i] / 64);
                ASSERT_EQ(explain_against(ta[i], tb[i], x, y).why.cause, d.causes[pixels[i]])
                    << name << " (" << x << ", " << y << ")";
            }
        }
    }
}

} // namespace
} // namespace glint
