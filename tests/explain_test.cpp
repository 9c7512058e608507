// `glint explain` in ray mode (hybrid: item_buffer_test.cpp): what it reports of a pixel is what
// the render wrote there, because it is the render's own path with a recorder.
#include "explain_shared.h"

namespace glint {
namespace {

FrameSettings ray_mode() {
    FrameSettings settings;
    settings.mode = Mode::ray;
    return settings;
}

// Every shipped scene with its own antialiasing (default.json: adaptive 3×3), at 160×120: a few
// hundred pixels each, random and on edges; at least some of them must have reflected or
// transmitted rays for the check to reach the recursion.
TEST(Explain, ReportsTheRenderedBytesAtHundredsOfPixelsOfEveryShippedScene) {
    for (const char* name : testing::kShippedScenes) {
        const Scene scene = testing::shipped(name, 160, 120);
        const World world(scene);
        const Frame frame = render_frame(world, ray_mode());
        const auto pixels = testing::pixels_to_explain(world, frame.result, 150);
        EXPECT_GE(pixels.size(), 200u) << name;
        const int secondary =
            testing::expect_explanations_match(scene, world, {}, frame.result, pixels, name);
        const bool recursive =
            std::any_of(world.objects().begin(), world.objects().end(), [&](const Object& o) {
                const Phong& m = world.geometry()->materials[o.material];
                return m.reflectivity > 0 || m.transmission > 0;
            });
        if (recursive) {
            EXPECT_GT(secondary, 10) << name << ": few pixels with reflected rays were explained";
        }
    }
}

// With one sample a pixel, explaining every pixel of the image counts exactly the render's rays.
TEST(Explain, EveryPixelsTreeSumsToTheRendersRayCounts) {
    for (const char* name : testing::kShippedScenes) {
        Scene scene = testing::shipped(name, 40, 30);
        scene.render.samples = 1;
        const World world(scene);
        const Frame frame = render_frame(world, ray_mode());
        RayCounts sum;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x) sum += explain_pixel(world, {}, x, y, 0, 0).tree_rays;
        EXPECT_EQ(sum.primary, frame.result.rays.primary) << name;
        EXPECT_EQ(sum.shadow, frame.result.rays.shadow) << name;
        EXPECT_EQ(sum.reflection, frame.result.rays.reflection) << name;
        EXPECT_EQ(sum.transmission, frame.result.rays.transmission) << name;
    }
}

// Uniform antialiasing: the pixel is its grid's mean, whichever sample is explained.
TEST(Explain, AUniformGridsPixelIsItsMeanForAnySample) {
    Scene scene = testing::shipped("glass", 64, 48);
    scene.render.samples = 2, scene.render.antialias = Antialias::uniform;
    const World world(scene);
    const Frame frame = render_frame(world, ray_mode());
    const Image bytes = frame.result.bytes();
    for (const auto& [x, y] : {std::pair{10, 10}, {32, 24}, {63, 47}}) {
        for (int s = 0; s < 4; ++s) {
            const PixelExplanation e = explain_pixel(world, {}, x, y, s % 2, s / 2);
            EXPECT_TRUE(e.averaged);
            const std::uint8_t* rendered = bytes.pixel(x, y);
            EXPECT_EQ(e.pixel_bytes,
                      (std::array<std::uint8_t, 3>{rendered[0], rendered[1], rendered[2]}));
        }
    }
}

// The lecture's sum holds in the recorded numbers: R_p = ambient + Σ(diffuse + specular) +
// Σ k·R_q, to float rounding (each term below 1e3 here; 1e-5 relative is 100 float ulps).
TEST(Explain, EachRaysColourIsTheSumOfItsRecordedTerms) {
    const Scene scene = testing::shipped("whitted", 80, 60);
    const World world(scene);
    for (int y = 0; y < 60; y += 7) {
        for (int x = 0; x < 80; x += 7) {
            const PixelExplanation e = explain_pixel(world, {}, x, y, 0, 0);
            for (const RecordedRay& r : e.rays) {
                if (!r.hit.found()) continue;
                Vec3 sum = r.ambient;
                for (const LightTerm& term : r.lights) sum += term.diffuse + term.specular;
                for (const int c : r.children)
                    sum += e.rays[static_cast<std::size_t>(c)].factor *
                           e.rays[static_cast<std::size_t>(c)].colour;
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(sum[k], r.colour[k], 1e-5 * (1 + std::abs(r.colour[k])));
            }
        }
    }
}

} // namespace
} // namespace glint
