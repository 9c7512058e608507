// Cut-outs (DESIGN §13) in the tracer: a hit whose alpha is below the material's cut-off is no
// hit, for every structure, single rays and packets, closest-hit and shadow queries alike, and
// the item buffer's one-object queries. The item buffer's id pass is held in
// tests/cut_out_gl_test.cpp.
#include "cut_out_scene.h"
#include "test_scenes.h"

#include "frame/explain.h"
#include "trace/explain.h"
#include "trace/render.h"
#include "trace/texture.h"
#include "trace/world.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

using testing::cut_out_scene;
using testing::kCutOutQuad;
using testing::kCutOutSphere;

// The ray from the eye through (x, y) on the quad's plane z = 1, camera-relative (as the World's
// rays are: the eye is the origin).
Ray through_quad(double x, double y) {
    return {Vec3(0), glm::normalize(Vec3(Real(x), Real(y), -4))};
}

TEST(CutOut, TheTextureAlphaIsSampledAsTheColourIs) {
    const Scene scene = cut_out_scene();
    const Texture& t = scene.textures[0];
    EXPECT_FLOAT_EQ(sample_alpha(t, {0.1f, 0.5f}), 0.0f);
    EXPECT_FLOAT_EQ(sample_alpha(t, {0.5f, 0.5f}), 0.5f);
    EXPECT_FLOAT_EQ(sample_alpha(t, {0.625f, 0.5f}), 0.75f);
    EXPECT_FLOAT_EQ(sample_alpha(t, {0.9f, 0.5f}), 1.0f);
    Texture opaque = t;
    auto image = std::make_shared<TextureImage>(*t.image);
    image->alpha.clear();
    opaque.image = image;
    EXPECT_FLOAT_EQ(sample_alpha(opaque, {0.1f, 0.5f}), 1.0f);
}

class CutOutStructures : public ::testing::TestWithParam<AccelKind> {};

// On the left half (x < 0) the ray passes the quad and meets the sphere (or the background
// beyond its outline); on the right it stops at the quad. Closest hits, any-hit shadow queries
// and their packets, with and without glass in the scene, and the one-object queries.
TEST_P(CutOutStructures, TheRayPassesTheMaskedHalfAndStopsAtTheOther) {
    for (const bool glass : {false, true}) {
        Scene scene = cut_out_scene();
        if (glass) scene.materials[0].transmission = 0.5f; // shadow rays count crossings
        const World world(scene, GetParam());
        std::vector<Ray> rays;
        for (double y = -1.9; y < 1.95; y += 0.25)
            for (double x = -1.9; x < 1.95; x += 0.2)
                if (std::abs(x) > 0.05) rays.push_back(through_quad(x, y));
        for (std::size_t first = 0; first < rays.size(); first += kMaxPacket) {
            const std::size_t count = std::min<std::size_t>(kMaxPacket, rays.size() - first);
            const std::span<const Ray> packet(&rays[first], count);
            Hit hits[kMaxPacket], one[kMaxPacket];
            world.intersect_packet(packet, hits);
            world.intersect_one_packet(kCutOutQuad, packet, one);
            // Shadow segments from the eye to z = 0.5: past the quad, short of the sphere.
            std::vector<Ray> shadows;
            for (const Ray& r : packet) shadows.push_back({r.origin, r.direction * Real(4.5 / -r.direction.z)});
            bool occluded[kMaxPacket], opaque[kMaxPacket], through[kMaxPacket];
            std::uint32_t skips[kMaxPacket];
            std::fill(std::begin(skips), std::end(skips), kNoObject);
            world.occluded_packet(shadows, 1, skips, occluded);
            world.opaque_between_packet(shadows, 1, skips, opaque, through);
            for (std::size_t k = 0; k < count; ++k) {
                const Ray& ray = packet[k];
                const bool masked = ray.direction.x < 0;
                const Hit hit = world.intersect(ray);
                SCOPED_TRACE("ray " + std::to_string(first + k) + (glass ? " with glass" : ""));
                if (masked) {
                    EXPECT_NE(hit.object, kCutOutQuad);
                    EXPECT_FALSE(world.intersect_one(kCutOutQuad, ray).found());
                } else {
                    EXPECT_EQ(hit.object, kCutOutQuad);
                    EXPECT_NEAR(hit.t, glm::length(Vec3(ray.direction) * Real(4 / -ray.direction.z)), 1e-4);
                }
                EXPECT_EQ(hits[k].object, hit.object);
                EXPECT_EQ(hits[k].t, hit.t);
                const Hit alone = world.intersect_one(kCutOutQuad, ray);
                EXPECT_EQ(one[k].found(), alone.found());
                EXPECT_EQ(one[k].t, alone.t);
                bool glass_seen = false;
                EXPECT_EQ(world.occluded(shadows[k], 1), !masked);
                EXPECT_EQ(world.opaque_between(shadows[k], 1, kNoObject, glass_seen), !masked);
                EXPECT_EQ(occluded[k], !masked);
                EXPECT_EQ(opaque[k], !masked);
            }
        }
    }
}

// A whole frame is the list's, byte for byte, and differs from the uncut quad's exactly where
// the mask is: the sphere shows through the left half and the quad's shadow falls only from the
// right half.
TEST_P(CutOutStructures, TheFrameIsTheListsAndTheMaskShows) {
    const Scene scene = cut_out_scene(48, 36);
    const Image list = render(World(scene, AccelKind::list)).bytes();
    EXPECT_EQ(render(World(scene, GetParam())).bytes().rgb, list.rgb);
    Scene solid = scene;
    solid.materials[1].cut_out = false;
    const Image uncut = render(World(solid, GetParam())).bytes();
    const auto pixel = [](const Image& image, int x, int y) {
        const std::uint8_t* p = image.pixel(x, y);
        return std::array<int, 3>{p[0], p[1], p[2]};
    };
    EXPECT_EQ(pixel(list, 36, 18), pixel(uncut, 36, 18)); // the right half: the quad
    EXPECT_NE(pixel(list, 14, 18), pixel(uncut, 14, 18)); // the left: the sphere shows
}

constexpr auto kCutOutStructures = all_values<AccelKind>();
INSTANTIATE_TEST_SUITE_P(EveryStructure, CutOutStructures,
                         ::testing::ValuesIn(kCutOutStructures.begin(), kCutOutStructures.end()),
                         [](const auto& info) { return std::string(name_of(info.param)); });

// A factor alone (no texture) cuts the whole object out or keeps it whole.
TEST(CutOut, AFactorBelowTheCutOffHidesTheWholeObject) {
    Scene scene = cut_out_scene();
    scene.materials[1].texture = kNoTexture;
    scene.materials[1].alpha = 0.4f;
    EXPECT_EQ(World(scene).intersect(through_quad(0.3, 0.2)).object, kCutOutSphere);
    scene.materials[1].alpha = 0.6f;
    EXPECT_EQ(World(scene).intersect(through_quad(0.3, 0.2)).object, kCutOutQuad);
}

// `glint explain` names the cut-out the primary ray passed through, with its alpha.
TEST(CutOut, ExplainShowsTheMaskedHitThatTheRayPassedThrough) {
    const Scene scene = cut_out_scene();
    const World world(scene);
    const int x = 26, y = 24; // the left half, on the sphere
    const PixelExplanation e = explain_pixel(world, {}, x, y, 0, 0);
    ASSERT_EQ(e.cut_through.size(), e.rays.size());
    ASSERT_EQ(e.cut_through[0].size(), 1u);
    EXPECT_EQ(e.cut_through[0][0].object, kCutOutQuad);
    EXPECT_LT(e.cut_through[0][0].alpha, 0.5f);
    EXPECT_EQ(e.rays[0].hit.object, kCutOutSphere);
    const std::string text = explanation_text(scene, world, e, "cut-out");
    EXPECT_NE(text.find("passes through object 1 at t = "), std::string::npos) << text;
    EXPECT_NE(text.find("cut out there (alpha 0"), std::string::npos) << text;
    const PixelExplanation right = explain_pixel(world, {}, 44, 24, 0, 0);
    EXPECT_TRUE(right.cut_through[0].empty());
    EXPECT_EQ(right.rays[0].hit.object, kCutOutQuad);
}

} // namespace
} // namespace glint
