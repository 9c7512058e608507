// The double-precision tracer as the float one's reference, and the reflection cut-off's error
// bound (trace/cutoff.h) checked pixel by pixel against renders that were not cut off.
#include "test_scenes.h"

#include "frame/frame.h"
#include "trace/cutoff.h"
#include "trace/image_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace glint {
namespace {

using testing::shipped;

// A ray-mode render through the frame layer, in either precision.
RenderResult ray_render(const Scene& scene, Precision precision = Precision::f32) {
    FrameSettings settings;
    settings.mode = Mode::ray;
    settings.precision = precision;
    return render_frame(scene, std::nullopt, settings).result;
}

class ShippedScene : public ::testing::TestWithParam<const char*> {};

// Float and double trace the same rays; they may part only where a ray grazes an edge (a pixel
// whose primary object differs, or whose reflection or shadow ray does). Tolerance: at most
// 0.2% of pixels off by more than 1/255 (at 200×150: 60 pixels, edges of curved outlines and
// shadow boundaries), and the float image within 45 dB of the double one overall.
TEST_P(ShippedScene, FloatRendersWhatTheDoublePrecisionReferenceRenders) {
    const Scene scene = shipped(GetParam(), 200, 150);
    const RenderResult single = ray_render(scene);
    const RenderResult reference = ray_render(scene, Precision::f64);
    EXPECT_GE(id_agreement(reference.ids, single.ids), 0.999);
    const ImageDifference diff = compare_images(reference.bytes(), single.bytes());
    EXPECT_LE(diff.fraction_over_one, 0.002);
    EXPECT_GE(diff.psnr_db, 45.0);
    EXPECT_EQ(reference.rays.primary, single.rays.primary);
}

// The reference tracer has no item buffer (that is drawn from the float world): asking for one
// is refused before anything is prepared, not silently traced by ray.
TEST(Precision, DoublePrecisionInHybridModeIsRefused) {
    FrameSettings settings;
    settings.precision = Precision::f64;
    EXPECT_THROW(render_frame(shipped("default", 8, 6), std::nullopt, settings),
                 std::invalid_argument);
}

// The bound is a bound: against a render of the same scene with reflections followed as deep as
// glint allows and no weight cut-off, every channel of every pixel of a truncated render lies
// below it by at least 0 and at most the pixel's bound. Both renders share every ray up to the
// cut, so nothing but the omitted term separates them.
TEST_P(ShippedScene, TheReflectionCutOffBoundHoldsOnEveryPixel) {
    const Scene scene_as_shipped = shipped(GetParam(), 160, 120);
    // A ray tree with glass branches twice at every hit, so "untruncated" cannot mean depth 64
    // without a weight cut-off there: each truncated render is compared with the same cut-off
    // at depth 24 instead. What separates the two is still only rays the truncated render
    // omitted (and counted), so the bound must hold the same way.
    bool glass = false;
    for (const Material& m : scene_as_shipped.materials) glass |= m.transmission > 0;
    for (const float cutoff : {0.0f, 0.01f, 0.1f}) {
        if (glass && cutoff == 0) continue;
        Scene deep = scene_as_shipped;
        deep.render = glass ? RenderSettings{24, cutoff} : RenderSettings{64, 0.0f};
        const Image untruncated = ray_render(deep).bytes();
        for (const int depth : {0, 1, 2, 3, 5, 8}) {
            Scene scene = deep;
            scene.render = {depth, cutoff};
            const RenderResult truncated = ray_render(scene);
            const CutoffBound bound = cutoff_bound(scene, truncated);
            const std::uint64_t violations = cutoff_violations(bound, truncated.bytes(), untruncated);
            EXPECT_EQ(violations, 0u) << "max_depth " << depth << ", min_reflectivity " << cutoff;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(testing::kShippedScenes),
                         [](const auto& info) { return info.param; });

// Two facing mirrors of reflectivity 0.9: what is cut off is at most 0.9^(depth+1) of what a
// ray can see, so the bound shrinks geometrically with depth, and once it is below 1/255 the
// render is the untruncated image.
TEST(Cutoff, TheBoundShrinksWithDepthBetweenFacingMirrors) {
    Scene scene = shipped("mirrors", 120, 90);
    scene.render.min_reflectivity = 0;
    int previous = 256;
    for (const int depth : {0, 4, 16, 64}) {
        scene.render.max_depth = depth;
        const CutoffBound bound = cutoff_bound(scene, ray_render(scene));
        EXPECT_LE(bound.max, previous) << "max_depth " << depth;
        previous = bound.max;
    }
    EXPECT_LE(previous, 1);
}

// Where nothing reflects, nothing is cut off, whatever the depth: the frame keeps no layer of
// weights (every one would be 0), its `cutoff` AOV is the image's size and 0, and its empty
// bound allows no channel to differ from the untruncated render.
TEST(Cutoff, ASceneWithoutMirrorsHasANullBound) {
    Scene scene = shipped("shadows", 80, 60);
    scene.render.max_depth = 0;
    const RenderResult render = ray_render(scene);
    EXPECT_TRUE(render.omitted_weight.empty());
    EXPECT_EQ(render.omitted_at(17), 0.0f);
    const CutoffBound bound = cutoff_bound(scene, render);
    EXPECT_EQ(bound.max, 0);
    EXPECT_EQ(bound.pixels_over_one, 0u);
    EXPECT_EQ(bound.largest_omitted_weight, 0.0);
    const std::vector<float> aov = cutoff_radiance(scene, render);
    EXPECT_EQ(aov.size(), std::size_t{80 * 60});
    EXPECT_EQ(std::count(aov.begin(), aov.end(), 0.0f), 80 * 60);

    const Image truncated = render.bytes();
    Image other = truncated;
    EXPECT_EQ(cutoff_violations(bound, truncated, other), 0u);
    other.rgb[3 * 1234 + 2] ^= 1; // one channel of one pixel, 1/255 apart
    EXPECT_EQ(cutoff_violations(bound, truncated, other), 1u);
}

// One material that reflects, or one that transmits, is enough for the frame to keep the
// layer, even at depth 0, where every such ray is omitted.
TEST(Cutoff, AnyReflectingOrTransmittingMaterialKeepsTheWeights) {
    for (const bool glass : {false, true}) {
        Scene scene = shipped("shadows", 40, 30);
        scene.render.max_depth = 0;
        Material& m = scene.materials.back();
        (glass ? m.transmission : m.reflectivity) = 0.5f;
        const RenderResult render = ray_render(scene);
        ASSERT_EQ(render.omitted_weight.size(), std::size_t{40 * 30}) << "glass " << glass;
        EXPECT_GT(cutoff_bound(scene, render).largest_omitted_weight, 0.0) << "glass " << glass;
    }
}

// The report's summary is the bound's figures, without its bytes per pixel.
TEST(Cutoff, TheSummaryHasTheBoundsFigures) {
    Scene scene = shipped("mirrors", 120, 90);
    for (const int depth : {0, 2, 6}) {
        scene.render.max_depth = depth;
        const RenderResult render = ray_render(scene);
        const CutoffBound bound = cutoff_bound(scene, render);
        const CutoffBound summary = cutoff_summary(scene, render);
        EXPECT_EQ(bound.per_pixel.size(), std::size_t{120 * 90});
        EXPECT_GT(bound.max, 0) << "depth " << depth;
        EXPECT_TRUE(summary.per_pixel.empty());
        EXPECT_EQ(summary.max, bound.max) << "depth " << depth;
        EXPECT_EQ(summary.pixels_over_one, bound.pixels_over_one) << "depth " << depth;
        EXPECT_EQ(summary.largest_omitted_weight, bound.largest_omitted_weight);
    }
}

} // namespace
} // namespace glint
