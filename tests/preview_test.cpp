// The preview's parts that need no window: the progressive refiner's finished image is the
// headless render, pixel for pixel; the orbit camera keeps its invariants; the views' colours.
#include "test_scenes.h"

#include "preview/orbit_camera.h"
#include "preview/refiner.h"
#include "preview/views.h"

#include "trace/image_metrics.h"
#include "trace/render.h"

#include <gtest/gtest.h>

#include <numeric>
#include <set>
#include <thread>

namespace glint {
namespace {

using testing::shipped;

// The item buffer of a camera as ray casting sees it: ids and view depths of the true hits.
std::shared_ptr<const IdImage> ids_by_ray(const World& world) {
    const std::vector<Hit> hits = primary_hits_by_ray(world);
    auto ids = std::make_shared<IdImage>();
    ids->width = world.camera().width(), ids->height = world.camera().height();
    ids->ids = object_ids(hits);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const int x = static_cast<int>(i % static_cast<std::size_t>(ids->width));
        const int y = static_cast<int>(i / static_cast<std::size_t>(ids->width));
        const float forward =
            glm::dot(world.camera().ray(x, y).direction, world.camera().forward());
        ids->view_depth.push_back(hits[i].found() ? hits[i].t * forward : kInfinity);
    }
    return ids;
}

void run_to_completion(const std::shared_ptr<RefineJob>& job, int threads) {
    Refiner refiner(threads);
    refiner.start(job);
    while (!job->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

class RefinerTest : public ::testing::TestWithParam<const char*> {};

// With samples, the preview refines after its first pass: the first pass is N = 1's image, and
// the finished job is the headless antialiased render (uniform and adaptive), from the same
// pixel-centre item buffer.
TEST_P(RefinerTest, TheSecondPassRefinesToTheScenesSamples) {
    for (const Antialias aa : {Antialias::uniform, Antialias::adaptive}) {
        Scene scene = shipped(GetParam(), 90, 70);
        scene.render.samples = 1;
        const RenderResult centres = render(World(scene));
        scene.render.samples = 3, scene.render.antialias = aa;
        const auto world = std::make_shared<const World>(scene);
        const RenderResult sampled = render(*world);
        auto job = std::make_shared<RefineJob>(world, ids_by_ray(*world), Resolve::exact);
        EXPECT_EQ(job->passes(), aa == Antialias::uniform ? 2 : 3);
        run_to_completion(job, 2);
        EXPECT_EQ(job->traced(View::final, 1).rgb, centres.bytes().rgb) << name_of(aa);
        EXPECT_EQ(job->traced(View::final).rgb, sampled.bytes().rgb) << name_of(aa);
        // Uniform: the preview's first pass comes on top of the grids, which render skips.
        EXPECT_EQ(job->rays().total(),
                  sampled.rays.total() + (aa == Antialias::uniform ? centres.rays.total() : 0))
            << name_of(aa);
        const auto refined = std::count(sampled.refined.begin(), sampled.refined.end(), 1);
        EXPECT_EQ(job->refined_pixels(),
                  aa == Antialias::uniform ? 90u * 70u : static_cast<std::uint64_t>(refined));
        for (int t = 0; t < job->tile_count(); ++t) EXPECT_EQ(job->tile_passes(t), job->passes());
    }
}

// Tile by tile, centre first, on any number of threads: the same bytes as shade_image over the
// same primary hits (ray mode, and hybrid from an id image), and the same ray counts.
TEST_P(RefinerTest, AFinishedJobIsTheHeadlessImage) {
    Scene scene = shipped(GetParam(), 150, 110);
    scene.render.samples = 1; // one pass; the next test refines to samples
    const auto world = std::make_shared<const World>(scene);
    const RenderResult by_ray = render(*world);
    for (const int threads : {1, 3}) {
        auto job = std::make_shared<RefineJob>(world, nullptr, Resolve::exact);
        run_to_completion(job, threads);
        EXPECT_EQ(job->traced(View::final).rgb, by_ray.bytes().rgb) << threads << " threads";
        EXPECT_EQ(job->rays().primary, by_ray.rays.primary);
        EXPECT_EQ(job->rays().shadow, by_ray.rays.shadow);
        EXPECT_EQ(job->rays().reflection, by_ray.rays.reflection);
        EXPECT_EQ(job->differing_pixels(), 0u) << "ray mode cannot differ from itself";
    }
    const auto ids = ids_by_ray(*world);
    PrimaryStats stats;
    const RenderResult hybrid =
        shade_image(*world, primary_hits(*world, {ids.get(), Resolve::exact}, stats));
    auto job = std::make_shared<RefineJob>(world, ids, Resolve::exact);
    run_to_completion(job, 2);
    EXPECT_EQ(job->traced(View::final).rgb, hybrid.bytes().rgb);
    EXPECT_EQ(job->primary_stats().exact_intersections, stats.exact_intersections);
    EXPECT_EQ(job->primary_stats().edges, stats.edges);
    EXPECT_GT(job->seconds(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, RefinerTest, ::testing::ValuesIn(testing::kShippedScenes),
                         [](const auto& info) { return info.param; });

// The difference view: with the comparison on, pixels whose resolved object is not the ray's are
// counted and shown red; without it no camera ray is cast and nothing differs. The id image is
// wrong on purpose (shifted by 9 columns) and trusted, so the resolve keeps its mistakes.
TEST(Refiner, TheDifferenceViewFindsWhereHybridAndRayDisagreeOnlyWhenAskedTo) {
    const auto world = std::make_shared<const World>(shipped("default", 120, 90));
    auto shifted = std::make_shared<IdImage>(*ids_by_ray(*world));
    for (int y = 0; y < 90; ++y)
        std::rotate(shifted->ids.begin() + y * 120, shifted->ids.begin() + y * 120 + 9,
                    shifted->ids.begin() + (y + 1) * 120);
    auto compared = std::make_shared<RefineJob>(world, shifted, Resolve::trust, true);
    run_to_completion(compared, 2);
    EXPECT_GT(compared->differing_pixels(), 100u);
    const Image& difference = compared->traced(View::difference);
    std::size_t red = 0;
    for (std::size_t i = 0; i < difference.rgb.size(); i += 3)
        red += difference.rgb[i] == 255 && difference.rgb[i + 1] == 0 && difference.rgb[i + 2] == 0;
    EXPECT_EQ(red, compared->differing_pixels());
    auto plain = std::make_shared<RefineJob>(world, shifted, Resolve::trust);
    run_to_completion(plain, 2);
    EXPECT_EQ(plain->differing_pixels(), 0u);
    EXPECT_EQ(plain->traced(View::final).rgb, compared->traced(View::final).rgb);
}

TEST(Refiner, TilesCoverTheImageOnceAndACancelledJobTracesNothing) {
    const auto world = std::make_shared<const World>(shipped("default", 100, 70));
    RefineJob job(world, nullptr, Resolve::exact);
    std::vector<int> covered(100 * 70, 0);
    for (int t = 0; t < job.tile_count(); ++t) {
        const TileRect r = job.tile(t);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) ++covered[static_cast<std::size_t>(y) * 100 + x];
    }
    EXPECT_EQ(std::set<int>(covered.begin(), covered.end()), std::set<int>{1});
    const std::atomic<bool> cancelled{true};
    job.run(cancelled, 2);
    EXPECT_EQ(job.tiles_done(), 0);
    EXPECT_FALSE(job.finished());
}

// A job stopped half-way leaves its finished tiles finished; a new one then runs to the end.
TEST(Refiner, StoppingAndRestartingRunsTheNewJobToTheEnd) {
    const auto world = std::make_shared<const World>(shipped("mirrors", 320, 240));
    Refiner refiner(2);
    auto first = std::make_shared<RefineJob>(world, nullptr, Resolve::exact);
    refiner.start(first);
    refiner.stop();
    const int done = first->tiles_done();
    int flagged = 0;
    for (int t = 0; t < first->tile_count(); ++t) flagged += first->tile_done(t);
    EXPECT_EQ(flagged, done);
    auto second = std::make_shared<RefineJob>(world, nullptr, Resolve::exact);
    refiner.start(second);
    while (!second->finished()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_EQ(first->tiles_done(), done) << "no tile of a stopped job is traced afterwards";
    EXPECT_EQ(second->traced(View::final).rgb, render(*world).bytes().rgb);
}

double distance(const Camera& c) {
    return glm::length(c.eye - c.look_at);
}

TEST(OrbitCamera, OrbitKeepsLookAtAndDistanceAndNeverFlipsOverTheUpAxis) {
    Camera home;
    home.eye = {3, 1, 4}, home.look_at = {1, 0, -1}, home.up = {0, 1, 0};
    OrbitCamera camera(home);
    camera.orbit(37, 12);
    EXPECT_EQ(camera.camera().look_at, home.look_at);
    EXPECT_NEAR(distance(camera.camera()), distance(home), 1e-12);
    EXPECT_NE(camera.camera().eye, home.eye);
    camera.orbit(0, 1000); // far past the pole
    const DVec3 offset = glm::normalize(camera.camera().eye - camera.camera().look_at);
    EXPECT_NEAR(std::acos(glm::dot(offset, DVec3(0, 1, 0))), glm::radians(1.0), 1e-9);
    camera.orbit(0, -1000);
    const DVec3 below = glm::normalize(camera.camera().eye - camera.camera().look_at);
    EXPECT_NEAR(std::acos(glm::dot(below, DVec3(0, 1, 0))), glm::radians(179.0), 1e-9);
    // A full turn of yaw comes back to where it started.
    OrbitCamera turning(home);
    for (int i = 0; i < 36; ++i) turning.orbit(10, 0);
    EXPECT_NEAR(glm::length(turning.camera().eye - home.eye), 0.0, 1e-9);
}

TEST(OrbitCamera, PanMovesEyeAndLookAtTogetherByThePixelsAtLookAtsDistance) {
    Camera home;
    home.eye = {0, 0, 10}, home.look_at = {0, 0, 0}, home.fov_y = 90, home.height = 200;
    OrbitCamera camera(home);
    camera.pan(10, 0); // 10 px of 200 with a view 20 units tall at distance 10: 1 unit
    EXPECT_NEAR(camera.camera().look_at.x, -1.0, 1e-12);
    EXPECT_NEAR(camera.camera().eye.x, -1.0, 1e-12);
    camera.pan(0, 20); // up 2 units: the scene follows the cursor up, so the camera goes down
    EXPECT_NEAR(camera.camera().look_at.y, -2.0, 1e-12);
    EXPECT_NEAR(distance(camera.camera()), 10.0, 1e-12);
}

TEST(OrbitCamera, DollyScalesTheDistanceStopsShortOfLookAtAndResetRestoresTheSceneCamera) {
    Camera home;
    home.eye = {0, 0, 10};
    OrbitCamera camera(home);
    camera.dolly(1);
    EXPECT_NEAR(distance(camera.camera()), 9.0, 1e-12);
    camera.dolly(-2);
    EXPECT_NEAR(distance(camera.camera()), 10.0 / 0.9, 1e-12);
    camera.dolly(1e6);
    EXPECT_NEAR(distance(camera.camera()), 1e-5, 1e-17);
    camera.resize(321, 123);
    camera.orbit(20, 20);
    camera.reset();
    EXPECT_EQ(camera.camera().eye, home.eye);
    EXPECT_EQ(camera.camera().width, 321) << "the window's size stays";
    EXPECT_EQ(camera.camera().height, 123);
}

TEST(Views, IdsGetDistinctColoursAndTheBackgroundBlack) {
    // The item-buffer view is `glint compare`'s false_colour.
    std::vector<std::uint32_t> ids(65);
    std::iota(ids.begin(), ids.end(), 0u);
    const Image image = false_colour(ids, 65, 1);
    EXPECT_EQ((Rgb{image.pixel(0, 0)[0], image.pixel(0, 0)[1], image.pixel(0, 0)[2]}),
              (Rgb{0, 0, 0}));
    std::set<Rgb> colours;
    for (int x = 1; x <= 64; ++x)
        colours.insert({image.pixel(x, 0)[0], image.pixel(x, 0)[1], image.pixel(x, 0)[2]});
    EXPECT_EQ(colours.size(), 64u);
    EXPECT_EQ(colours.count(Rgb{0, 0, 0}), 0u);
}

TEST(Views, DepthIsBrightestNearestDarkestFarthestAndBlackWhereNothingWasDrawn) {
    IdImage ids;
    ids.width = 3, ids.height = 1;
    ids.ids = {1, 2, 0};
    ids.view_depth = {2.0f, 200.0f, kInfinity};
    const Image image = depth_image(ids);
    EXPECT_EQ(image.pixel(0, 0)[0], 255);
    EXPECT_EQ(image.pixel(1, 0)[0], to_byte(0.15f));
    EXPECT_EQ(image.pixel(2, 0)[0], 0);
}

} // namespace
} // namespace glint
