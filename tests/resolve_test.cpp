// The item buffer's resolve without GL (trace/primary_hits.cpp, the exact-mode argument): id
// images made by casting every pixel's (or sample's) ray, then spoiled the ways a rasterizer
// spoils them (nothing drawn where an object is, another object named, a drawn depth short of
// the true one), are resolved exactly, and must give ray mode's hits and frame bit for bit. With
// no GL context this runs in both test trees: under the sanitizers it is what holds the resolve,
// its bins and a hybrid frame's passes to ASan and UBSan (the GL tests run in Release only).
#include "test_scenes.h"

#include "trace/cutoff.h"
#include "trace/primary_hits.h"
#include "trace/render.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace glint {
namespace {

// How a synthetic id image departs from the true one, pixel by pixel.
enum class Spoil { none, mixed };

// A deterministic hash of a block of pixels: which spoiling it gets.
std::uint32_t block_hash(std::uint32_t x, std::uint32_t y) {
    std::uint32_t h = x * 0x9E3779B1u ^ (y + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15, h *= 0xC2B2AE3Du, h ^= h >> 13;
    return h;
}

// The id image an ideal rasterizer would draw of `world` at n× its size (sample (a, b) of pixel
// (i, j) at (n·i + a, n·j + b), as PrimarySource::sample_ids): each sample ray's first object and
// its view depth. Spoiled, in blocks of 4×4 pixels (so that a block's inner pixels are no id
// boundary, where the resolve tests every object, but are held to the depth interval alone):
// about one block in eight names nothing although objects are there, one in eight names one
// object throughout (at the true nearest depths, as where GL and the tracer disagree), and one
// in eight has its depths halved (an enclosing tessellation drawn in front of the true surface):
// every departure the exact argument allows.
IdImage synthetic_ids(const World& world, int n, Spoil spoil) {
    const PinholeCamera& camera = world.camera();
    IdImage ids;
    ids.width = camera.width() * n;
    ids.height = camera.height() * n;
    const std::size_t pixels = static_cast<std::size_t>(ids.width) * ids.height;
    ids.ids.assign(pixels, 0);
    ids.view_depth.assign(pixels, kInfinity);
    const auto objects = static_cast<std::uint32_t>(world.objects().size());
    for (int y = 0; y < ids.height; ++y)
        for (int x = 0; x < ids.width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * ids.width + x;
            const Ray ray = camera.sample_ray(x / n, y / n, x % n, y % n, n);
            const Hit hit = world.intersect(ray);
            if (!hit.found()) continue;
            ids.ids[p] = hit.object + 1;
            ids.view_depth[p] =
                static_cast<float>(hit.t * glm::dot(ray.direction, camera.forward()));
            if (spoil == Spoil::none) continue;
            const std::uint32_t h =
                block_hash(static_cast<std::uint32_t>(x / 4), static_cast<std::uint32_t>(y / 4));
            switch (h % 8) {
            case 0: // nothing drawn
                ids.ids[p] = 0;
                ids.view_depth[p] = kInfinity;
                break;
            case 1: // one object named throughout, in front of which nothing was drawn
                ids.ids[p] = (h >> 3) % objects + 1;
                break;
            case 2: // drawn in front of the true surface
                ids.view_depth[p] *= 0.5f;
                break;
            default:
                break;
            }
        }
    bin_objects(world, ids);
    return ids;
}

// Every shipped scene, small: the claim holds at any size.
class ResolveTest : public ::testing::TestWithParam<const char*> {
  protected:
    Scene scene() const {
        return testing::shipped(GetParam(), 96 / testing::kSanitizerShrink,
                                72 / testing::kSanitizerShrink);
    }
    // The scene with N×N samples a pixel and the antialiasing rule.
    Scene sampled(int samples, Antialias antialias) const {
        Scene s = scene();
        s.render.samples = samples;
        s.render.antialias = antialias;
        return s;
    }
};

// The frames' passes a whole-frame test goes through: pixel centres alone, a uniform grid, and
// adaptive's centres then its refined samples.
constexpr std::pair<int, Antialias> kSamplings[] = {
    {1, Antialias::uniform}, {2, Antialias::uniform}, {3, Antialias::adaptive}};

TEST_P(ResolveTest, ExactResolveOfASpoiledIdImageGivesEveryRayModeHit) {
    const Scene s = scene();
    const World world(s);
    for (const Spoil spoil : {Spoil::none, Spoil::mixed}) {
        const IdImage ids = synthetic_ids(world, 1, spoil);
        PrimaryStats stats;
        const std::vector<Hit> resolved = primary_hits(world, {&ids, Resolve::exact}, stats);
        const std::vector<Hit> cast = primary_hits_by_ray(world);
        ASSERT_EQ(resolved.size(), cast.size());
        for (std::size_t i = 0; i < cast.size(); ++i) {
            ASSERT_EQ(resolved[i].object, cast[i].object) << "pixel " << i;
            ASSERT_EQ(resolved[i].t, cast[i].t) << "pixel " << i;
            ASSERT_EQ(resolved[i].primitive, cast[i].primitive) << "pixel " << i;
        }
        if (spoil == Spoil::mixed && world.objects().size() > 1) {
            EXPECT_GT(stats.fallbacks + stats.corrected, 0u) << "the spoiled ids were all harmless";
        }
    }
}

TEST_P(ResolveTest, TrustResolveOfATrueIdImageNamesRayModesObjects) {
    const Scene s = scene();
    const World world(s);
    const IdImage ids = synthetic_ids(world, 1, Spoil::none);
    PrimaryStats stats;
    const std::vector<Hit> resolved = primary_hits(world, {&ids, Resolve::trust}, stats);
    const std::vector<Hit> cast = primary_hits_by_ray(world);
    for (std::size_t i = 0; i < cast.size(); ++i)
        ASSERT_EQ(resolved[i].object, cast[i].object) << "pixel " << i;
}

// A whole hybrid frame from spoiled ids, through the same passes as every frame (pixel centres;
// a uniform grid's ids; adaptive's centres then its refined samples) equals ray mode's bit for
// bit: colour, bytes, ids and AOVs.
TEST_P(ResolveTest, AFrameFromSpoiledIdsIsRayModesFrame) {
    for (const auto& [samples, antialias] : kSamplings) {
        const Scene s = sampled(samples, antialias);
        const World world(s);
        const IdImage centres = synthetic_ids(world, 1, Spoil::mixed);
        const IdImage grid = synthetic_ids(world, samples, Spoil::mixed);
        // As frame/frame.cpp's primary_source draws them: uniform grids resolve the grid's ids;
        // adaptive resolves the centres' and casts the refined pixels' samples (the grid's ids
        // would add rule 3, --aa-sample-ids, which may differ from ray mode by design).
        PrimarySource source{&centres, Resolve::exact};
        if (samples > 1 && antialias == Antialias::uniform)
            source = {nullptr, Resolve::exact, &grid};
        PrimaryStats stats, unused;
        PhaseTimes times;
        const RenderResult hybrid =
            trace_frame(world, source, stats, {}, times, testing::with_aovs());
        const RenderResult ray = trace_frame(world, {}, unused, {}, times, testing::with_aovs());
        const std::string what = std::to_string(samples) + "x" + std::to_string(samples) + " " +
                                 std::string(name_of(antialias));
        EXPECT_EQ(hybrid.radiance.rgb, ray.radiance.rgb) << what;
        EXPECT_EQ(hybrid.bytes().rgb, ray.bytes().rgb) << what;
        EXPECT_EQ(hybrid.ids, ray.ids) << what;
        EXPECT_EQ(hybrid.aovs.depth, ray.aovs.depth) << what;
        EXPECT_EQ(hybrid.aovs.normal, ray.aovs.normal) << what;
    }
}

// A frame that keeps no float image (FrameRequest::radiance false, `glint render` to a PNG) makes
// its display bytes as it stores each pixel: they are the float frame's bytes, and so is every
// figure its report reads (the cut-off bound's, from those bytes and the weights), in ray mode
// and from spoiled ids, with one sample, a uniform grid and adaptive antialiasing (whose rule
// reads the first pass's bytes).
TEST_P(ResolveTest, AFrameOfBytesAloneHasTheFloatFramesBytes) {
    for (const auto& [samples, antialias] : kSamplings) {
        Scene s = sampled(samples, antialias);
        s.render.max_depth = 2; // omits rays where a material reflects: the bound is not 0
        const World world(s);
        const IdImage centres = synthetic_ids(world, 1, Spoil::mixed);
        FrameRequest bytes_alone;
        bytes_alone.radiance = false;
        for (const PrimarySource& source : {PrimarySource{}, PrimarySource{&centres}}) {
            PrimaryStats stats;
            PhaseTimes times;
            const RenderResult floats = trace_frame(world, source, stats, {}, times);
            const RenderResult bytes = trace_frame(world, source, stats, {}, times, bytes_alone);
            const std::string what = std::to_string(samples) + "x" + std::to_string(samples) + " " +
                                     std::string(name_of(antialias)) +
                                     (source.ids ? ", hybrid" : ", ray");
            EXPECT_TRUE(floats.floats() && !bytes.floats()) << what;
            EXPECT_TRUE(bytes.radiance.empty() && bytes.clamped.empty()) << what;
            EXPECT_EQ(bytes.width(), floats.width()) << what;
            EXPECT_EQ(bytes.pixels(), floats.pixels()) << what;
            EXPECT_EQ(bytes.bytes().rgb, floats.bytes().rgb) << what;
            EXPECT_EQ(bytes.refined, floats.refined) << what;
            EXPECT_EQ(bytes.omitted_weight, floats.omitted_weight) << what;
            const CutoffBound a = cutoff_summary(s, floats), b = cutoff_summary(s, bytes);
            EXPECT_EQ(b.max, a.max) << what;
            EXPECT_EQ(b.pixels_over_one, a.pixels_over_one) << what;
            EXPECT_EQ(b.largest_omitted_weight, a.largest_omitted_weight) << what;
        }
    }
}

// A tile's primary hits hand their camera rays on to its shading (trace/passes.cpp): each kept
// ray is the camera's own for its pixel, bit for bit, in ray mode and from the item buffer
// (exact and trust, spoiled ids: pixels resolved alone, blocks as one packet, the background),
// and keeping them changes no hit. The tile is cut off at the image's edge and its rows are
// strided as a frame-wide buffer's.
TEST_P(ResolveTest, APixelsKeptCameraRayIsTheCamerasRay) {
    const Scene s = scene();
    const World world(s);
    const PinholeCamera& camera = world.camera();
    const IdImage ids = synthetic_ids(world, 1, Spoil::mixed);
    const TileRect tile{5, 3, camera.width(), camera.height() - 1};
    const auto stride = static_cast<std::size_t>(camera.width());
    const auto same_ray = [](const Ray& a, const Ray& b) {
        return std::memcmp(&a.origin, &b.origin, sizeof a.origin) == 0 &&
               std::memcmp(&a.direction, &b.direction, sizeof a.direction) == 0;
    };
    for (const PrimarySource source : {PrimarySource{}, PrimarySource{&ids, Resolve::exact},
                                       PrimarySource{&ids, Resolve::trust}}) {
        const std::size_t n = stride * static_cast<std::size_t>(tile.y1 - tile.y0);
        std::vector<Hit> alone(n), kept(n);
        std::vector<Ray> rays(n);
        PrimaryStats stats;
        tile_primary_hits(world, source, tile, alone.data(), stride, stats);
        tile_primary_hits(world, source, tile, kept.data(), stride, stats, rays.data());
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t at = static_cast<std::size_t>(y - tile.y0) * stride +
                                       static_cast<std::size_t>(x - tile.x0);
                ASSERT_TRUE(same_ray(rays[at], camera.ray(x, y))) << x << ", " << y;
                ASSERT_EQ(kept[at].object, alone[at].object) << x << ", " << y;
                ASSERT_EQ(kept[at].t, alone[at].t) << x << ", " << y;
            }
    }
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, ResolveTest, ::testing::ValuesIn(testing::kShippedScenes),
                         [](const auto& info) { return std::string(info.param); });

} // namespace
} // namespace glint
