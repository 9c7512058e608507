// Two settings compared pixel by pixel (frame/difference.h, trace/ray_tree.h): each differing
// pixel's cause is the first place its two ray trees part (DESIGN §13), a setting against itself
// differs nowhere, the tallies add up, and `explain --against` names the cause the map shows.
// Ray mode here (every tree and rule without GL); the hybrid sides are in item_buffer_test.cpp.
#include "difference_shared.h"
#include "frame/difference_maps.h"
#include "frame/explain_against.h"
#include "io/error.h"
#include "test_scenes.h"

#include <gtest/gtest.h>

#include <numeric>

namespace glint {
namespace {

// A ray-mode float side of `scene` whose render settings `change` sets.
template <class Change> Side ray_side(const Scene& scene, const Change& change) {
    Side side;
    side.scene = scene;
    side.frame.mode = Mode::ray;
    change(side);
    return side;
}
Side ray_side(const Scene& scene) {
    return ray_side(scene, [](Side&) {});
}

Side exact_side(const Scene& scene) {
    Side side = ray_side(scene);
    make_exact(side);
    return side;
}

// The causes that occur, with their pixel counts.
std::map<Cause, std::uint64_t> causes_of(const FrameDifference& d) {
    std::map<Cause, std::uint64_t> out;
    for (const Cause c : d.causes)
        if (c != Cause::none) ++out[c];
    return out;
}

void expect_only(const FrameDifference& d, Cause cause, const std::string& what) {
    EXPECT_GT(d.differing, 0u) << what << ": nothing differs, so the test shows nothing";
    EXPECT_EQ(d.tallies[static_cast<std::size_t>(cause)].pixels, d.differing) << what;
    for (const auto& [c, n] : causes_of(d))
        EXPECT_EQ(c, cause) << what << ": " << n << " pixels " << name_of(c);
}

// Two facing mirrors: only the depth limit differs, so the trees part where one stops.
TEST(Difference, OnlyTheDepthLimitDiffersEveryPixelIsDepth) {
    Scene scene = testing::shipped("mirrors", 96, 72);
    scene.render.samples = 1;
    const RenderedSide a(ray_side(scene, [](Side& s) { s.scene.render.max_depth = 2; }));
    const RenderedSide b(ray_side(scene, [](Side& s) { s.scene.render.max_depth = 10; }));
    const FrameDifference d = difference(a, b, false);
    expect_only(d, Cause::depth, "mirrors, depth 2 against 10");
    // Depth 2 stops rays at level 3: every pixel parts there.
    const auto& levels = d.tallies[static_cast<std::size_t>(Cause::depth)].levels;
    ASSERT_EQ(levels.size(), 4u);
    EXPECT_EQ(levels[3], d.differing);
}

TEST(Difference, OnlyTheCutoffDiffersEveryPixelIsCutoff) {
    Scene scene = testing::shipped("mirrors", 96, 72);
    scene.render.samples = 1;
    const RenderedSide a(ray_side(scene, [](Side& s) { s.scene.render.min_reflectivity = 0.2f; }));
    const RenderedSide b(
        ray_side(scene, [](Side& s) { s.scene.render.min_reflectivity = 0.001f; }));
    expect_only(difference(a, b, false), Cause::cutoff, "mirrors, cut-off 0.2 against 0.001");
}

TEST(Difference, OneSampleAgainstAGridIsSampling) {
    Scene scene = testing::shipped("default", 96, 72);
    scene.render.antialias = Antialias::uniform;
    const RenderedSide a(ray_side(scene, [](Side& s) { s.scene.render.samples = 1; }));
    const RenderedSide b(ray_side(scene, [](Side& s) { s.scene.render.samples = 3; }));
    expect_only(difference(a, b, false), Cause::sampling, "default, 1x1 against 3x3");
}

// Every shipped scene's setting against itself: nothing differs, and the cause map is grey.
TEST(Difference, ASideAgainstItselfDiffersNowhere) {
    for (const char* name : testing::kShippedScenes) {
        // Under the sanitizers a quarter of the pixels (test_scenes.h): the exact frames at
        // depth 64 dominate, and the claim holds at any size.
        const Scene scene =
            testing::shipped(name, 48 / testing::kSanitizerShrink, 36 / testing::kSanitizerShrink);
        for (const bool exact : {false, true}) {
            const Side side = exact ? exact_side(scene) : ray_side(scene);
            const RenderedSide a(side), b(side);
            const FrameDifference d = difference(a, b, true);
            EXPECT_EQ(d.differing, 0u) << name;
            EXPECT_EQ(d.largest, 0.0) << name;
            const Image map = cause_map(d, a.frame().result.bytes());
            for (int y = 0; y < d.height; ++y)
                for (int x = 0; x < d.width; ++x) {
                    const std::uint8_t* p = map.pixel(x, y);
                    ASSERT_TRUE(p[0] == p[1] && p[1] == p[2])
                        << name << " (" << x << ", " << y << ")";
                }
        }
    }
}

// The tallies add up: pixels to the differing pixels, shares to 1, squared errors to the total.
TEST(Difference, TheCausesPixelsAndSharesAddUp) {
    for (const char* name : testing::kShippedScenes) {
        const Scene scene =
            testing::shipped(name, 64 / testing::kSanitizerShrink, 48 / testing::kSanitizerShrink);
        const RenderedSide a(ray_side(scene, [](Side& s) { s.scene.render.max_depth = 1; }));
        const RenderedSide b(exact_side(scene));
        const FrameDifference d = difference(a, b, false);
        std::uint64_t pixels = 0;
        double shares = 0, squared = 0;
        for (std::size_t c = 0; c < kCauses; ++c) {
            pixels += d.tallies[c].pixels;
            shares += d.share(static_cast<Cause>(c));
            squared += d.tallies[c].squared_error;
            if (d.tallies[c].levels.empty()) continue;
            EXPECT_EQ(std::accumulate(d.tallies[c].levels.begin(), d.tallies[c].levels.end(),
                                      std::uint64_t{0}),
                      d.tallies[c].pixels)
                << name << ": " << name_of(static_cast<Cause>(c)) << "'s levels";
        }
        EXPECT_EQ(d.tallies[0].pixels, 0u) << name;
        EXPECT_EQ(pixels, d.differing) << name;
        EXPECT_EQ(static_cast<std::uint64_t>(std::count_if(
                      d.causes.begin(), d.causes.end(), [](Cause c) { return c != Cause::none; })),
                  d.differing)
            << name;
        if (d.differing > 0) {
            EXPECT_NEAR(shares, 1.0, 1e-9) << name;
        }
        EXPECT_NEAR(squared, d.squared_error, 1e-12 + 1e-9 * d.squared_error) << name;
    }
}

// A node's share is weight × its own terms: a tree's shares sum to its primary ray's colour.
TEST(Difference, ATreesSharesSumToItsColour) {
    const Scene scene = testing::shipped("whitted", 32, 24);
    const RenderedSide side(ray_side(scene));
    std::vector<std::uint32_t> pixels(32 * 24);
    std::iota(pixels.begin(), pixels.end(), 0u);
    for (const PixelTrees& trees : side.trees(pixels))
        for (const SampleTree& tree : trees.samples) {
            DVec3 sum(0);
            for (const TreeNode& node : tree) sum += node.share();
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k], tree.front().colour[k], 1e-5);
        }
}

// Float against the exact image at the same depth and no cut-off: the trees part by precision
// alone where they match, and some pixels do.
TEST(Difference, FloatAgainstDoubleAtTheSameSettingsIsMostlyPrecision) {
    Scene scene = testing::shipped("default", 64, 48);
    const RenderedSide a(ray_side(scene, [](Side& s) {
        s.scene.render.max_depth = kMaxDepth, s.scene.render.min_reflectivity = 0;
    }));
    const RenderedSide b(exact_side(scene));
    const FrameDifference d = difference(a, b, true); // radiance: a float output's rule
    EXPECT_GT(d.tallies[static_cast<std::size_t>(Cause::precision)].pixels, d.differing / 2);
    EXPECT_EQ(d.tallies[static_cast<std::size_t>(Cause::depth)].pixels, 0u);
    EXPECT_EQ(d.tallies[static_cast<std::size_t>(Cause::cutoff)].pixels, 0u);
}

// `explain --against`'s cause at 200 pixels of each shipped scene (the differing ones first) is
// the cause map's there.
TEST(Difference, ExplainAgainstAgreesWithTheCauseMap) {
    for (const char* name : testing::kShippedScenes) {
        // 64x48, or 32x24 under the sanitizers: still 200 pixels to check.
        constexpr int width = 64 / testing::kSanitizerShrink;
        const Scene scene = testing::shipped(name, width, 48 / testing::kSanitizerShrink);
        const std::pair<Side, Side> pairs[] = {
            {ray_side(scene, [](Side& s) { s.scene.render.max_depth = 1; }), exact_side(scene)},
            {ray_side(scene, [](Side& s) { s.scene.render.min_reflectivity = 0.3f; }),
             ray_side(scene, [](Side& s) { s.scene.render.samples = 2; })},
        };
        for (const auto& [side_a, side_b] : pairs) {
            const RenderedSide a(side_a), b(side_b);
            const FrameDifference d = difference(a, b, false);
            const std::vector<std::uint32_t> pixels = testing::pixels_to_check(d);
            ASSERT_EQ(pixels.size(), 200u) << name;
            const auto ta = a.trees(pixels), tb = b.trees(pixels);
            for (std::size_t i = 0; i < pixels.size(); ++i) {
                const int x = static_cast<int>(pixels[i] % width),
                          y = static_cast<int>(pixels[i] / width);
                const PixelAgainst p = explain_against(ta[i], tb[i], x, y);
                ASSERT_EQ(p.why.cause, d.causes[pixels[i]])
                    << name << " (" << x << ", " << y << "): explain says " << name_of(p.why.cause)
                    << ", the map " << name_of(d.causes[pixels[i]]);
            }
        }
    }
}

// The cause map paints each cause its own colour, and the heat map's top is the largest error
// or below it.
TEST(Difference, TheMapsShowEachCauseAndTheErrorScale) {
    Scene scene = testing::shipped("mirrors", 96, 72);
    scene.render.samples = 1;
    const RenderedSide a(ray_side(scene, [](Side& s) { s.scene.render.max_depth = 2; }));
    const RenderedSide b(exact_side(scene));
    const FrameDifference d = difference(a, b, false);
    const Image causes = cause_map(d, a.frame().result.bytes());
    ASSERT_EQ(causes.width, 96);
    EXPECT_GT(causes.height, 72); // the legend below
    for (int y = 0; y < 72; ++y)
        for (int x = 0; x < 96; ++x) {
            const Cause c = d.causes[static_cast<std::size_t>(y) * 96 + x];
            if (c == Cause::none) continue;
            const Rgb want = cause_colour(c);
            ASSERT_TRUE(std::equal(want.begin(), want.end(), causes.pixel(x, y)));
        }
    EXPECT_LE(heat_top(d), d.largest * 1.1);
    EXPECT_GT(heat_top(d), 0.0);
    const Image heat = heat_map(d);
    EXPECT_EQ(heat.width, 96);
    EXPECT_GT(heat.height, 72);
}

} // namespace
} // namespace glint
