// The render loop: identical bytes for any thread count, the golden image of the default scene,
// and spawned rays that never re-hit the surface they leave (no acne), at scales 1e-3 … 1e3.
#include "test_scenes.h"

#include "trace/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

namespace glint {
namespace {

Scene default_scene(int width, int height) {
    Scene scene = load_scene(GLINT_SOURCE_DIR "/scenes/default.json");
    scene.camera.width = width, scene.camera.height = height;
    return scene;
}

TEST(Render, OneAndTwoThreadsGiveIdenticalBytes) {
    const World world(default_scene(203, 151)); // sizes that leave partial tiles
    const RenderResult one = render(world, {1, nullptr});
    const RenderResult two = render(world, {2, nullptr});
    EXPECT_EQ(one.image.rgb, two.image.rgb);
    EXPECT_EQ(one.rays.shadow, two.rays.shadow);
    EXPECT_EQ(one.rays.reflection, two.rays.reflection);
}

TEST(Render, ProgressCountsEveryTile) {
    const World world(default_scene(100, 70));
    std::atomic<int> done{0};
    render(world, {0, &done});
    EXPECT_EQ(done.load(), 2 * tile_count(100, 70)); // primary hits, then shading
    EXPECT_EQ(tile_count(100, 70), 4 * 3);
}

// The default scene against tests/data/default_160x120.png (how it was made: tests/data/README.md).
// Tolerance: every channel within 2/255, except at most 0.5% of pixels, which may differ by
// anything: at silhouettes and shadow edges a change of one ulp in t (another compiler or libm)
// flips a pixel between two objects. A real change to shading or geometry moves far more.
TEST(Render, DefaultSceneMatchesTheGoldenImage) {
    const Image golden = read_png(GLINT_SOURCE_DIR "/tests/data/default_160x120.png");
    const Image image = render(World(default_scene(160, 120))).image;
    ASSERT_EQ(image.width, golden.width);
    ASSERT_EQ(image.height, golden.height);
    int off = 0;
    for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
        bool pixel_off = false;
        for (int c = 0; c < 3; ++c) pixel_off |= std::abs(image.rgb[i + c] - golden.rgb[i + c]) > 2;
        off += pixel_off;
    }
    EXPECT_LE(off, image.width * image.height / 200) << off << " pixels differ by more than 2/255";
}

// Convex shapes: a ray leaving a hit point on the side its normal faces can never meet the same
// object again. Any hit on it is self-intersection from rounding, the cause of acne.
class NoAcneTest : public ::testing::TestWithParam<std::tuple<const char*, double>> {};

TEST_P(NoAcneTest, SpawnedRaysNeverRehitTheSurfaceTheyLeave) {
    const auto [shape, scale] = GetParam();
    const std::string extra = std::string(shape) == "triangle"
                                  ? R"(, "vertices": [[-1, -1, 0], [1, -1, 0.3], [0, 1, -0.2]])"
                              : std::string(shape) == "cone" ? R"(, "top_radius": 0.4)"
                                                             : "";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    int spawned = 0;
    for (int trial = 0; trial < 30; ++trial) {
        // A random rotated, non-uniformly scaled object of size `scale`, 4·scale from the camera.
        const std::string s = std::to_string(scale);
        const Scene scene = testing::scene_at_origin(
            R"([{"shape": ")" + std::string(shape) + R"(", "transform": [{"scale": [)" +
            std::to_string(scale * (1 + 0.5 * u(rng))) + ", " +
            std::to_string(scale * (1 + 0.5 * u(rng))) + ", " +
            std::to_string(scale * (1 + 0.5 * u(rng))) + R"(]}, {"rotate": {"axis": [)" +
            std::to_string(u(rng)) + ", 1, " + std::to_string(u(rng)) + R"(], "degrees": )" +
            std::to_string(180 * u(rng)) + R"(}}, {"translate": [0, 0, )" +
            std::to_string(-4 * scale) + "]}]" + extra + "}]");
        const World world(scene);
        for (int k = 0; k < 200; ++k) {
            const Ray primary{Vec3(0.0f), glm::normalize(Vec3(0.3f * u(rng), 0.3f * u(rng), -1))};
            const Hit hit = world.intersect(primary);
            if (!hit.found()) continue;
            const SurfacePoint p = world.surface(primary, hit);
            // Reflection, and a random direction into the facing hemisphere (shadow rays).
            Vec3 random(u(rng), u(rng), u(rng));
            if (glm::dot(random, p.normal) < 0) random = -random;
            for (Vec3 d : {reflect(primary.direction, p.normal), random}) {
                if (glm::dot(d, p.normal) <= 1e-3f * glm::length(d))
                    continue; // grazing: tangent rays may touch
                const Hit again = world.intersect({p.spawn(), d});
                EXPECT_FALSE(again.found())
                    << shape << " at scale " << scale << ": re-hit at t = " << again.t;
                ++spawned;
            }
        }
    }
    EXPECT_GT(spawned, 1000);
}

INSTANTIATE_TEST_SUITE_P(ConvexShapesAtEveryScale, NoAcneTest,
                         ::testing::Combine(::testing::Values("sphere", "box", "disk", "plane",
                                                              "cylinder", "cone", "triangle"),
                                            ::testing::Values(1e-3, 1.0, 1e3)),
                         [](const auto& info) {
                             const double scale = std::get<1>(info.param);
                             return std::string(std::get<0>(info.param)) + (scale < 1   ? "_small"
                                                                            : scale > 1 ? "_large"
                                                                                        : "_unit");
                         });

TEST(Output, AFailedWriteLeavesTheOldFileAndNoTemporaryFile) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(::testing::TempDir()) / "glint_output_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "taken");
    write_file_atomically(dir / "a.txt", "old");
    write_file_atomically(dir / "a.txt", "new"); // replaced whole
    // Renaming over a directory fails after the temporary file was written.
    EXPECT_THROW(write_file_atomically(dir / "taken", "bytes"), std::runtime_error);
    EXPECT_TRUE(fs::is_directory(dir / "taken"));
    EXPECT_THROW(write_file_atomically(dir / "missing" / "a.txt", "bytes"), std::runtime_error);
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"a.txt", "taken"}));
    std::ifstream in(dir / "a.txt");
    std::string text;
    in >> text;
    EXPECT_EQ(text, "new");
}

TEST(Render, RayCountsAddUp) {
    const Scene scene = default_scene(40, 30);
    const RenderResult r = render(World(scene));
    EXPECT_EQ(r.rays.primary, 40u * 30u);
    // Two lights: at most two shadow rays per shaded hit.
    EXPECT_LE(r.rays.shadow, 2 * (r.rays.primary + r.rays.reflection));
}

} // namespace
} // namespace glint
