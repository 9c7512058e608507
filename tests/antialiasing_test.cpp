// Antialiasing (DESIGN §11, docs/ANTIALIASING.md): the sample grid's rays, a half-covered pixel's
// hand-computed mean, one sample as today's pixel centre, the same bytes for any thread count,
// and the adaptive rule: which pixels it refines, and that they equal the uniform grid's.
#include "test_scenes.h"

#include "trace/render.h"
#include "trace/sampling.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

Scene default_scene(int width, int height, int samples, Antialias aa = Antialias::uniform) {
    Scene scene = testing::shipped("default", width, height);
    scene.render.samples = samples;
    scene.render.antialias = aa;
    return scene;
}

// (a + 0.5)/N is exactly 0.5 for an odd grid's centre, so its ray is the pixel centre's, bit for
// bit: uniform odd grids and adaptive passes agree with N = 1 there.
TEST(Antialiasing, TheCentreSampleOfAnOddGridIsThePixelCentre) {
    const World world(default_scene(37, 23, 1));
    const PinholeCamera& camera = world.camera();
    for (const int n : {1, 3, 5, 15}) {
        for (const auto& [i, j] : {std::pair{0, 0}, {36, 22}, {17, 5}}) {
            const Ray centre = camera.ray(i, j), sample = camera.sample_ray(i, j, n / 2, n / 2, n);
            EXPECT_EQ(centre.direction, sample.direction) << n << ": " << i << ", " << j;
        }
    }
    // And the grid's corners lie (a + 0.5)/N into the pixel: pixel (0, 0)'s first sample of 2×2
    // is the centre of pixel (0, 0) of an image twice the size.
    const World twice(default_scene(74, 46, 1));
    EXPECT_NEAR(glm::distance(camera.sample_ray(0, 0, 0, 0, 2).direction,
                              twice.camera().ray(0, 0).direction),
                0.0f, 1e-6f);
}

// One box covers the left half of a 1×1 image: of the 2×2 samples, a = 0 see the box, a = 1 the
// background. The box's colour is its ambient (2, 0.5, 0.2) under a white scene ambient and no
// light; clamped per sample to (1, 0.5, 0.2), averaged with the background (0, 0, 0.6):
// (0.5, 0.25, 0.4), bytes round(255·…) = (128, 64, 102). Clamping the mean instead of each
// sample would give red 255.
TEST(Antialiasing, AHalfCoveredPixelIsTheMeanOfItsClampedSamples) {
    Scene scene = testing::scene_at_origin(
        R"([{"shape": "box", "material": "glow",
             "transform": [{"scale": 5}, {"translate": [-5, 0, -7]}]}])",
        R"({"glow": {"ambient": [2, 0.5, 0.2], "diffuse": [0, 0, 0], "specular": [0, 0, 0]}})",
        "[]", R"(, "ambient": [1, 1, 1], "background": [0, 0, 0.6])");
    scene.camera.width = scene.camera.height = 1;
    scene.camera.fov_y = 90;
    scene.render.samples = 2;
    const RenderResult result = render(World(scene));
    const Image bytes = result.bytes();
    const std::uint8_t* p = bytes.pixel(0, 0);
    EXPECT_EQ(p[0], 128);
    EXPECT_EQ(p[1], 64);
    EXPECT_EQ(p[2], 102);
    EXPECT_EQ(result.rays.primary, 4u);
}

// N = 1 is trace/pixel.h's pixel centre: the frame is shade_image over the centres' hits, and
// asking for adaptive with one sample changes nothing.
TEST(Antialiasing, OneSampleIsThePixelCentresImage) {
    const World world(default_scene(64, 48, 1));
    const RenderResult centres = shade_image(world, primary_hits_by_ray(world));
    EXPECT_EQ(render(world).bytes().rgb, centres.bytes().rgb);
    const World adaptive(default_scene(64, 48, 1, Antialias::adaptive));
    const RenderResult one = render(adaptive);
    EXPECT_EQ(one.bytes().rgb, centres.bytes().rgb);
    EXPECT_TRUE(one.refined.empty());
}

TEST(Antialiasing, OneAndTwoThreadsGiveIdenticalBytesForEveryGrid) {
    for (const Antialias aa : {Antialias::uniform, Antialias::adaptive}) {
        for (int n = 1; n <= kMaxSamples; ++n) {
            // Partial tiles; larger where the grid is small enough to afford it.
            const int w = n <= 4 ? 67 : 19, h = n <= 4 ? 45 : 13;
            const World world(default_scene(w, h, n, aa));
            const RenderResult one = render(world, {1, nullptr});
            const RenderResult two = render(world, {2, nullptr});
            EXPECT_EQ(one.bytes().rgb, two.bytes().rgb) << name_of(aa) << " " << n;
            EXPECT_EQ(one.rays.total(), two.rays.total()) << name_of(aa) << " " << n;
            EXPECT_EQ(one.refined, two.refined) << name_of(aa) << " " << n;
        }
    }
}

// Adaptive is N = 1's image with the refined pixels replaced by the uniform grid's, exactly;
// the shipped scenes' edges make it refine some pixels and leave most.
TEST(Antialiasing, AdaptivePixelsAreTheUniformGridsWhereRefinedAndTheCentresElsewhere) {
    for (const char* name : testing::kShippedScenes) {
        for (const int n : {2, 3}) {
            Scene scene = testing::shipped(name, 80, 60);
            scene.render.samples = 1;
            const RenderResult centres = render(World(scene));
            scene.render.samples = n;
            const RenderResult uniform = render(World(scene));
            scene.render.antialias = Antialias::adaptive;
            const RenderResult adaptive = render(World(scene));
            ASSERT_EQ(adaptive.refined.size(), 80u * 60u);
            std::size_t refined = 0;
            const Image uniform_bytes = uniform.bytes(), centre_bytes = centres.bytes();
            const Image adaptive_bytes = adaptive.bytes();
            for (int y = 0; y < 60; ++y) {
                for (int x = 0; x < 80; ++x) {
                    const bool r = adaptive.refined[std::size_t(y) * 80 + x];
                    refined += r;
                    const Image& expected = r ? uniform_bytes : centre_bytes;
                    ASSERT_TRUE(std::equal(expected.pixel(x, y), expected.pixel(x, y) + 3,
                                           adaptive_bytes.pixel(x, y)))
                        << name << " " << n << ": " << x << ", " << y;
                }
            }
            EXPECT_GT(refined, 0u) << name;
            // glass.json's checker floor has cells of a pixel or two at this size: 79% refined.
            EXPECT_LT(refined, 80u * 60u * 9 / 10) << name;
            EXPECT_EQ(adaptive.ids, centres.ids) << name;
        }
    }
}

// The rule itself on a 6×5 image: one pixel with another path key refines itself and its 8
// neighbours; a colour step above the threshold refines both sides; mixed sample ids refine
// only their own pixel.
TEST(Antialiasing, TheAdaptiveRuleRefinesAroundKeysContrastAndMixedSampleIds) {
    const int w = 6, h = 5;
    Image image(w, h);
    std::vector<std::uint64_t> keys(w * h, 7);
    keys[2 * w + 1] = 8; // pixel (1, 2)
    const auto refined = [&](const IdImage* ids, float threshold) {
        return adaptive_refinement(image, keys, ids, 2, threshold);
    };
    std::vector<std::uint8_t> r = refined(nullptr, 0.1f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(r[y * w + x], std::abs(x - 1) <= 1 && std::abs(y - 2) <= 1) << x << "," << y;

    keys.assign(w * h, 7);
    image.pixel(5, 0)[1] = 26; // a step of 26/255 ≈ 0.102 between (5, 0) and its neighbours
    r = refined(nullptr, 0.1f);
    EXPECT_EQ(std::count(r.begin(), r.end(), 1), 4); // (5, 0) and (4, 0), (4, 1), (5, 1)
    EXPECT_EQ(r[0 * w + 4], 1);
    EXPECT_EQ(r[1 * w + 5], 1);
    r = refined(nullptr, 0.11f); // 26 ≤ floor(0.11·255) = 28
    EXPECT_EQ(std::count(r.begin(), r.end(), 1), 0);

    IdImage ids{2 * w, 2 * h, std::vector<std::uint32_t>(4 * w * h, 3), {}, {}};
    ids.ids[(2 * 3 + 1) * ids.width + 2 * 4] = 5; // a sample of pixel (4, 3)
    r = refined(&ids, 0.5f);
    EXPECT_EQ(std::count(r.begin(), r.end(), 1), 1);
    EXPECT_EQ(r[3 * w + 4], 1);
}

// Rule 4: around a refined pixel whose grid's mean differs from its centre by more than the
// threshold, the unrefined neighbours are refined next; a refined pixel that changed less adds
// nothing.
TEST(Antialiasing, RefinementSpreadsWhereAGridFoundMoreThanItsCentre) {
    const int w = 5, h = 4;
    const Image first(w, h);
    Image current(w, h);
    std::vector<std::uint8_t> refined(w * h, 0);
    refined[1 * w + 1] = refined[1 * w + 2] = refined[2 * w + 4] = 1;
    current.pixel(1, 1)[2] = 30; // 30/255 > 0.1: spreads
    current.pixel(4, 2)[0] = 20; // 20/255 < 0.1: does not
    std::size_t added = 0;
    const std::vector<std::uint8_t> next = adaptive_spread(first, current, refined, 0.1f, added);
    EXPECT_EQ(added, 7u); // (1, 1)'s 8 neighbours but refined (2, 1)
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(next[y * w + x],
                      std::abs(x - 1) <= 1 && std::abs(y - 1) <= 1 && !refined[y * w + x])
                << x << ", " << y;
}

TEST(Antialiasing, UniformGridsCastNSquaredPrimaryRaysAndAverageTheCutOffWeights) {
    const World one(default_scene(40, 30, 1));
    const World four(default_scene(40, 30, 4));
    const RenderResult a = render(one), b = render(four);
    EXPECT_EQ(b.rays.primary, 16u * 40 * 30);
    EXPECT_TRUE(b.refined.empty());
    float largest_a = 0, largest_b = 0;
    for (std::size_t i = 0; i < a.omitted_weight.size(); ++i)
        largest_a = std::max(largest_a, a.omitted_weight[i]),
        largest_b = std::max(largest_b, b.omitted_weight[i]);
    EXPECT_GT(largest_b, 0);
    EXPECT_LE(largest_b, 1.01f * std::max(largest_a, largest_b)); // a mean of per-sample weights
}

} // namespace
} // namespace glint
