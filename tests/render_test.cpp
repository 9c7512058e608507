// The render loop: identical bytes for any thread count, the golden image of the default scene,
// and spawned rays that never re-hit the surface they leave (no acne), at scales 1e-3 … 1e3.
#include "test_scenes.h"

#include "io/png.h"
#include "io/write_file.h"
#include "trace/render.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

namespace glint {
namespace {

// scenes/default.json with one sample a pixel (antialiasing_test.cpp tests its samples).
Scene default_scene(int width, int height) {
    Scene scene = load_scene(GLINT_SOURCE_DIR "/scenes/default.json");
    scene.camera.width = width, scene.camera.height = height;
    scene.render.samples = 1;
    return scene;
}

TEST(Render, OneAndTwoThreadsGiveIdenticalBytes) {
    const World world(default_scene(203, 151)); // sizes that leave partial tiles
    const RenderResult one = render(world, {1, nullptr});
    const RenderResult two = render(world, {2, nullptr});
    EXPECT_EQ(one.bytes().rgb, two.bytes().rgb);
    EXPECT_EQ(one.rays.shadow, two.rays.shadow);
    EXPECT_EQ(one.rays.reflection, two.rays.reflection);
}

// trace/pixel.h's path is the frame's: a pixel traced alone has the colour, rays and cut-off
// weight that shade_image gives it, and its normal is the surface's own shading normal.
TEST(Render, APixelTracedAloneIsThePixelOfTheFrame) {
    const World world(default_scene(64, 48));
    const std::vector<Hit> primary = primary_hits_by_ray(world);
    const RenderResult frame = shade_image(world, primary);
    const Image bytes = frame.bytes();
    RayCounts total;
    int hits = 0;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x) {
            PrimaryStats stats;
            const PixelSample sample = trace_pixel(world, {}, x, y, stats);
            const std::size_t i = static_cast<std::size_t>(y) * 64 + x;
            std::uint8_t rgb[3];
            store_colour(sample.colour, rgb);
            ASSERT_TRUE(std::equal(rgb, rgb + 3, bytes.pixel(x, y))) << x << ", " << y;
            EXPECT_EQ(static_cast<float>(sample.omitted_weight), frame.omitted_weight[i]);
            EXPECT_EQ(sample.hit.found(), primary[i].found());
            total += sample.rays;
            if (!sample.hit.found()) {
                EXPECT_EQ(sample.normal, Vec3(0));
                continue;
            }
            ++hits;
            EXPECT_EQ(sample.normal, world.surface(world.camera().ray(x, y), sample.hit).shading);
        }
    }
    EXPECT_GT(hits, 64 * 48 / 2);
    EXPECT_EQ(total.primary, frame.rays.primary);
    EXPECT_EQ(total.shadow, frame.rays.shadow);
    EXPECT_EQ(total.reflection, frame.rays.reflection);
}

// A camera move (docs/PREVIEW.md): the World for the new camera shares the old one's meshes
// and refits its structure, and renders exactly what a World made afresh for that camera does,
// for every structure, on every shipped scene (instances.json places OBJ meshes).
TEST(Render, AWorldForAMovedCameraRendersWhatAFreshWorldDoes) {
    for (const char* name : testing::kShippedScenes) {
        for (const AccelKind kind : all_values<AccelKind>()) {
            Scene scene = testing::shipped(name, 64, 48);
            const World before(scene, kind);
            scene.camera.eye = scene.camera.eye * 1.3 + DVec3(0.7, 0.4, -0.2);
            scene.camera.width = 72, scene.camera.height = 40;
            scene.render.max_depth = 3;
            const World moved(scene, before);
            const World fresh(scene, kind);
            EXPECT_EQ(moved.accelerator().kind(), kind);
            EXPECT_EQ(render(moved).bytes().rgb, render(fresh).bytes().rgb)
                << name << ", " << name_of(kind);
            if (!scene.meshes.empty()) {
                EXPECT_EQ(&moved.mesh(0), &before.mesh(0)) << name << ": a mesh was prepared again";
            }
        }
    }
}

TEST(Render, ProgressCountsEveryTile) {
    const World world(default_scene(100, 70));
    std::atomic<int> done{0};
    render(world, {0, &done});
    // One pass (trace/passes.h): each tile's primary hits and shading together.
    EXPECT_EQ(done.load(), tile_count(100, 70));
    EXPECT_EQ(progress_steps(world.settings(), 100, 70), tile_count(100, 70));
    EXPECT_EQ(tile_count(100, 70), 4 * 3);
}

// The default scene against tests/data/default_160x120.png (how it was made: tests/data/README.md).
// Tolerance: every channel within 2/255, except at most 0.5% of pixels, which may differ by
// anything: at silhouettes and shadow edges a change of one ulp in t (another compiler or libm)
// flips a pixel between two objects. A real change to shading or geometry moves far more.
TEST(Render, DefaultSceneMatchesTheGoldenImage) {
    const Image golden = read_png(GLINT_SOURCE_DIR "/tests/data/default_160x120.png");
    const Image image = render(World(default_scene(160, 120))).bytes();
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

// Convex solids left from outside and planar shapes: rays leaving on the normal's side can
// never meet the object again, so they skip it and start on the surface (no offset).
TEST(Spawn, ConvexAndPlanarSurfacesAreSkippedNotOffset) {
    const Scene scene = testing::scene_at_origin(R"([
        {"shape": "sphere", "transform": [{"translate": [-3, 0, -8]}]},
        {"shape": "box", "transform": [{"translate": [0, 0, -8]}]},
        {"shape": "cone", "top_radius": 0.4, "transform": [{"translate": [3, -0.5, -8]}]},
        {"shape": "disk", "transform": [{"rotate": {"axis": [1, 0, 0], "degrees": 80}}, {"translate": [0, 3, -8]}]},
        {"shape": "mesh", "vertices": [[-1, -4, -8], [1, -4, -8], [0, -2, -8], [0, -3, -6]], "indices": [0, 1, 3, 1, 2, 3]}])");
    const World world(scene);
    for (const Vec3 target : {Vec3(-3, 0, -7), Vec3(0, 0, -7), Vec3(3, 0, -7), Vec3(0, 3, -8)}) {
        const Ray ray{Vec3(0.0f), glm::normalize(target)};
        const Hit hit = world.intersect(ray);
        ASSERT_TRUE(hit.found());
        const SurfacePoint p = world.surface(ray, hit);
        EXPECT_EQ(p.skip, hit.object);
        EXPECT_EQ(p.offset, 0.0f);
    }
    // A mesh may be concave: its points are offset, never skipped.
    const Ray ray{Vec3(0.0f), glm::normalize(Vec3(0, -3, -7))};
    const Hit hit = world.intersect(ray);
    ASSERT_EQ(hit.object, 4u);
    const SurfacePoint p = world.surface(ray, hit);
    EXPECT_EQ(p.skip, kNoObject);
    EXPECT_GT(p.offset, 0.0f);
}

// Where an offset is still needed (the inside of solids, whose reflections meet them again,
// and meshes, which may be concave), a ray spawned at the offset point never meets the face it
// left right there: a hit on it within 1e-4 of the object's size is self-intersection from
// rounding (at ~1e-6 of the size without the offset), the cause of acne.
class NoAcneTest : public ::testing::TestWithParam<std::tuple<const char*, double>> {};

TEST_P(NoAcneTest, SpawnedRaysNeverRehitTheSurfaceTheyLeave) {
    const auto [shape, scale] = GetParam();
    const std::string name = shape;
    const bool mesh = name == "mesh";
    // Inside solids are centred on the camera (cylinders and cones span y in [0, 1]); the mesh, a
    // concave fold of two triangles, sits 4·scale in front of it.
    const std::string centre =
        name == "cylinder" || name == "cone" ? R"({"translate": [0, -0.5, 0]}, )" : "";
    const std::string extra =
        mesh
            ? R"(, "vertices": [[-1, -1, 0], [1, -1, 0], [0, 1, 0.8], [0, -1, -1.5]], "indices": [0, 3, 2, 3, 1, 2])"
        : name == "cone" ? R"(, "top_radius": 0.4)"
                         : "";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1, 1);
    int spawned = 0;
    for (int trial = 0; trial < 30; ++trial) {
        // A random rotated, non-uniformly scaled object of size `scale`.
        const Scene scene = testing::scene_at_origin(
            R"([{"shape": ")" + name + R"(", "transform": [)" + centre + R"({"scale": [)" +
            std::to_string(scale * (1 + 0.5 * u(rng))) + ", " +
            std::to_string(scale * (1 + 0.5 * u(rng))) + ", " +
            std::to_string(scale * (1 + 0.5 * u(rng))) + R"(]}, {"rotate": {"axis": [)" +
            std::to_string(u(rng)) + ", 1, " + std::to_string(u(rng)) + R"(], "degrees": )" +
            std::to_string(180 * u(rng)) + R"(}}, {"translate": [0, 0, )" +
            std::to_string(mesh ? -4 * scale : 0.0) + "]}]" + extra + "}]");
        const World world(scene);
        for (int k = 0; k < 200; ++k) {
            const Ray primary{Vec3(0.0f), glm::normalize(Vec3(0.3f * u(rng), 0.3f * u(rng), -1))};
            const Hit hit = world.intersect(primary);
            if (!hit.found()) continue;
            const SurfacePoint p = world.surface(primary, hit);
            ASSERT_EQ(p.skip, kNoObject) << "this case is about the offset";
            // Reflection, and a random direction into the facing hemisphere (shadow rays).
            Vec3 random(u(rng), u(rng), u(rng));
            if (glm::dot(random, p.normal) < 0) random = -random;
            for (Vec3 d : {reflect(primary.direction, p.normal), random}) {
                if (glm::dot(d, p.normal) <= 1e-3f * glm::length(d))
                    continue; // grazing: tangent rays may touch
                const Hit again = world.intersect({p.spawn(), d});
                // The same face or part: a plane, or a curve whose chord for a non-grazing ray
                // is at least ~1e-3 of its radius; other faces may legitimately be near.
                EXPECT_FALSE(again.object == hit.object && again.primitive == hit.primitive &&
                             again.t < 1e-4 * scale * glm::length(d))
                    << shape << " at scale " << scale << ": re-hit at t = " << again.t;
                ++spawned;
            }
        }
    }
    EXPECT_GT(spawned, 1000);
}

INSTANTIATE_TEST_SUITE_P(InsideSolidsAndMeshesAtEveryScale, NoAcneTest,
                         ::testing::Combine(::testing::Values("sphere", "box", "cylinder", "cone",
                                                              "mesh"),
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

TEST(Output, PngsDecodeToEveryPixelWrittenAtSizesThatSplitIntoBands) {
    // write_png deflates bands of 64 rows in parallel into one zlib stream (io/png.cpp).
    // Each image must come back byte for byte through an independent decoder (stb_image), and
    // its stream must pass zlib's own checks (uncompress verifies the combined Adler-32).
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(::testing::TempDir()) / "glint_png_test";
    fs::create_directories(dir);
    std::mt19937 rng(7);
    for (const auto& [w, h] : {std::pair{1, 1}, {3, 63}, {5, 64}, {2, 65}, {257, 130}, {40, 200}}) {
        Image image(w, h);
        for (std::size_t i = 0; i < image.rgb.size(); ++i)
            image.rgb[i] = static_cast<std::uint8_t>(i % 7 == 0 ? rng() : i / 5);
        const fs::path path = dir / ("p" + std::to_string(w) + "x" + std::to_string(h) + ".png");
        write_png(path, image);
        const Image back = read_png(path);
        EXPECT_EQ(back.width, w);
        EXPECT_EQ(back.height, h);
        EXPECT_EQ(back.rgb, image.rgb) << w << "x" << h;

        const std::string png = encode_png(image);
        const std::size_t idat = 8 + 25; // signature and IHDR
        ASSERT_EQ(png.substr(idat + 4, 4), "IDAT");
        const auto length =
            static_cast<std::uint32_t>(static_cast<unsigned char>(png[idat]) << 24 |
                                       static_cast<unsigned char>(png[idat + 1]) << 16 |
                                       static_cast<unsigned char>(png[idat + 2]) << 8 |
                                       static_cast<unsigned char>(png[idat + 3]));
        std::vector<Bytef> raw(static_cast<std::size_t>(w * 3 + 1) * h);
        uLongf raw_size = static_cast<uLongf>(raw.size());
        EXPECT_EQ(uncompress(raw.data(), &raw_size,
                             reinterpret_cast<const Bytef*>(png.data() + idat + 8), length),
                  Z_OK)
            << w << "x" << h;
        EXPECT_EQ(raw_size, raw.size());
    }
}

TEST(Output, PngsEncodedFromFloatRowsDecodeToTheirBytes) {
    // glint render quantises a frame's float rows as the bands are deflated (row_bytes through
    // PngRows), each thread reusing its buffers from band to band. The file must decode
    // (stb_image) to to_byte (to_srgb_byte) of every value, and be the file encode_png makes of
    // the 8-bit image, at sizes whose last band is short, on one thread and on two.
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(::testing::TempDir()) / "glint_png_rows_test";
    fs::create_directories(dir);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> colour(-0.25f, 1.25f);
    for (const std::pair<int, int>& size :
         {std::pair{1, 1}, {7, 64}, {33, 65}, {300, 200}, {1920, 131}}) {
        // Not a structured binding: the lambdas below capture them, which clang 14 refuses.
        const int w = size.first, h = size.second;
        FloatImage image(w, h);
        for (std::size_t i = 0; i < image.rgb.size(); ++i) {
            // Halfway values (k + 0.5)/255, NaN and infinities beside random colours.
            const int kind = static_cast<int>(rng() % 16);
            image.rgb[i] = kind == 0   ? (static_cast<float>(rng() % 255) + 0.5f) / 255.0f
                           : kind == 1 ? std::numeric_limits<float>::quiet_NaN()
                           : kind == 2 ? std::numeric_limits<float>::infinity()
                                       : colour(rng);
        }
        for (const int threads : {1, 2}) {
            tbb::task_arena arena(threads);
            for (const bool srgb : {false, true}) {
                const std::string at = std::to_string(w) + "x" + std::to_string(h) + ", " +
                                       std::to_string(threads) + " threads, srgb " +
                                       std::to_string(srgb);
                const PngRows rows = [&](int y, std::uint8_t* out) {
                    row_bytes(image, y, srgb, out);
                };
                const fs::path path = dir / "rows.png";
                arena.execute([&] { write_png(path, w, h, rows); });
                const Image back = read_png(path);
                ASSERT_EQ(back.width, w);
                ASSERT_EQ(back.height, h);
                for (std::size_t i = 0; i < image.rgb.size(); ++i)
                    ASSERT_EQ(back.rgb[i],
                              srgb ? to_srgb_byte(image.rgb[i]) : to_byte(image.rgb[i]))
                        << at << ", value " << i << ": " << image.rgb[i];
                EXPECT_EQ(arena.execute([&] { return encode_png(w, h, rows); }), encode_png(back))
                    << at;
            }
        }
    }
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
