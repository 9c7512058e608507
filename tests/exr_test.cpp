// The float frame (trace/render_result.h) and what is written from it: an EXR read back by the
// OpenEXR library's own reader equals the float image and the AOVs; the float image is the
// double tracer's within a stated tolerance and keeps radiance above 1; the AOVs are what the
// tracer computes for each pixel centre.
#include "test_scenes.h"

#include "frame/frame.h"
#include "io/exr.h"
#include "trace/cutoff.h"
#include "trace/render.h"
#include "trace/sampling.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

namespace glint {
namespace {

namespace fs = std::filesystem;
using testing::kShippedScenes;
using testing::shipped;
using testing::with_aovs;

RenderResult ray_render(const Scene& scene, Precision precision = Precision::f32,
                        bool aovs = false) {
    FrameSettings settings;
    settings.mode = Mode::ray;
    settings.precision = precision;
    settings.aovs = aovs;
    return render_frame(scene, std::nullopt, settings).result;
}

// Every channel of an EXR file as floats (UINT channels converted), by name, through OpenEXR's
// own reader.
std::map<std::string, std::vector<float>> read_exr(const fs::path& path, int& width,
                                                   int& height,
                                                   std::map<std::string, Imf::PixelType>& types) {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    std::map<std::string, std::vector<float>> channels;
    std::map<std::string, std::vector<std::uint32_t>> uints;
    Imf::FrameBuffer buffer;
    for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c) {
        types[c.name()] = c.channel().type;
        const std::size_t pixels = static_cast<std::size_t>(width) * height;
        if (c.channel().type == Imf::UINT) {
            auto& v = uints[c.name()];
            v.resize(pixels);
            buffer.insert(c.name(), Imf::Slice(Imf::UINT, reinterpret_cast<char*>(v.data()),
                                               sizeof(std::uint32_t),
                                               sizeof(std::uint32_t) * width));
        } else {
            auto& v = channels[c.name()];
            v.resize(pixels);
            buffer.insert(c.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()),
                                               sizeof(float), sizeof(float) * width));
        }
    }
    file.setFrameBuffer(buffer);
    file.readPixels(window.min.y, window.max.y);
    for (const auto& [name, v] : uints) channels[name].assign(v.begin(), v.end());
    return channels;
}

// A lit sphere under a light three times as bright as white: radiance well above 1 on its lit
// side, below it in the penumbra and ambient.
Scene bright_scene(int width, int height) {
    Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0], "fov_y": 40},
        "background": [0.2, 0.4, 1.5], "ambient": [0.1, 0.1, 0.1],
        "lights": [{"position": [3, 4, 5], "color": [3, 3, 3]}],
        "materials": {"m": {"diffuse": [0.7, 0.5, 0.3], "specular": [0.6, 0.6, 0.6],
                            "shininess": 30, "reflectivity": 0.3}},
        "objects": [{"shape": "sphere", "material": "m"},
                    {"shape": "plane", "material": "m",
                     "transform": [{"translate": [0, -1, 0]}]}]})",
                              "bright.json");
    scene.camera.width = width, scene.camera.height = height;
    return scene;
}

TEST(Exr, OpenExrsReaderGivesBackTheFloatImageAndEveryAov) {
    Scene scene = shipped("default", 48, 36);
    const RenderResult result = ray_render(scene, Precision::f32, true);
    const std::vector<float> cutoff = cutoff_radiance(scene, result);
    const fs::path path = fs::path(::testing::TempDir()) / "glint_exr_test.exr";
    write_exr(path, {&result.radiance, &result.aovs.depth, &result.aovs.normal, &result.aovs.id,
                     &cutoff});
    int width = 0, height = 0;
    std::map<std::string, Imf::PixelType> types;
    const auto channels = read_exr(path, width, height, types);
    fs::remove(path);
    ASSERT_EQ(width, 48);
    ASSERT_EQ(height, 36);
    const std::map<std::string, Imf::PixelType> expected_types = {
        {"R", Imf::FLOAT},   {"G", Imf::FLOAT},   {"B", Imf::FLOAT},  {"Z", Imf::FLOAT},
        {"N.X", Imf::FLOAT}, {"N.Y", Imf::FLOAT}, {"N.Z", Imf::FLOAT}, {"id", Imf::UINT},
        {"cutoff", Imf::FLOAT}};
    EXPECT_EQ(types, expected_types);
    for (std::size_t i = 0; i < static_cast<std::size_t>(width) * height; ++i) {
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(channels.at(std::string(1, "RGB"[c]))[i], result.radiance.rgb[3 * i + c]);
            ASSERT_EQ(channels.at(c == 0 ? "N.X" : c == 1 ? "N.Y" : "N.Z")[i],
                      result.aovs.normal[3 * i + c]);
        }
        ASSERT_EQ(channels.at("Z")[i], result.aovs.depth[i]) << i;
        ASSERT_EQ(channels.at("id")[i], static_cast<float>(result.aovs.id[i])) << i;
        ASSERT_EQ(channels.at("cutoff")[i], cutoff[i]) << i;
    }
}

TEST(Exr, WithoutAovsTheFileHoldsRgbOnly) {
    const RenderResult result = ray_render(shipped("primitives", 16, 12));
    const fs::path path = fs::path(::testing::TempDir()) / "glint_exr_rgb.exr";
    write_exr(path, {&result.radiance});
    int width = 0, height = 0;
    std::map<std::string, Imf::PixelType> types;
    const auto channels = read_exr(path, width, height, types);
    fs::remove(path);
    EXPECT_EQ(channels.size(), 3u);
    EXPECT_EQ(channels.at("G"), std::vector<float>([&] {
                  std::vector<float> g;
                  for (std::size_t i = 1; i < result.radiance.rgb.size(); i += 3)
                      g.push_back(result.radiance.rgb[i]);
                  return g;
              }()));
}

// The float image against the double tracer (the reference) on a scene whose radiance exceeds 1.
// Tolerance: |float − double| ≤ 1e-3 · max(1, double) on pixels whose primary object agrees and
// whose 8 neighbours' do too (a silhouette's pixel may see another object in either precision).
// The float tracer's hit points carry a few ulps of relative error (~1e-6), which shading's
// handful of products and the specular power (×30 in relative error) and one reflection
// bounce raise to ~1e-4 at most; 1e-3 is that with a margin, and a quarter of one 8-bit step.
TEST(FloatFrame, MatchesTheDoubleTracerAndKeepsRadianceAboveOne) {
    const Scene scene = bright_scene(120, 90);
    const RenderResult single = ray_render(scene);
    const RenderResult reference = ray_render(scene, Precision::f64);
    const int width = scene.camera.width, height = scene.camera.height;
    double largest = 0, brightest = 0;
    int compared = 0;
    for (int y = 1; y + 1 < height; ++y) {
        for (int x = 1; x + 1 < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            bool interior = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    interior &= reference.ids[i + dy * width + dx] == reference.ids[i] &&
                                single.ids[i + dy * width + dx] == reference.ids[i];
            if (!interior) continue;
            ++compared;
            for (int c = 0; c < 3; ++c) {
                const double want = reference.radiance.rgb[3 * i + c];
                const double got = single.radiance.rgb[3 * i + c];
                EXPECT_NEAR(got, want, 1e-3 * std::max(1.0, std::abs(want)))
                    << x << ", " << y << " channel " << c;
                largest = std::max(largest, std::abs(got - want));
                brightest = std::max(brightest, want);
            }
        }
    }
    EXPECT_GT(compared, width * height / 2);
    EXPECT_GT(brightest, 2.0) << "the lit side's radiance is kept above 1";
    // The PNG's bytes clamp it: 255 where the radiance is above 1.
    const Image bytes = single.bytes();
    for (std::size_t k = 0; k < single.radiance.rgb.size(); ++k)
        if (single.radiance.rgb[k] > 1) {
            ASSERT_EQ(bytes.rgb[k], 255);
        }
    RecordProperty("largest_difference", std::to_string(largest));
}

// N×N samples: the float image is the mean of the unclamped samples, the PNG's bytes the
// rounded mean of the clamped ones (DESIGN §11, §12), and the two differ where a sample is above
// 1.
TEST(FloatFrame, AGridKeepsTheUnclampedMeanBesideTheClampedOne) {
    Scene scene = bright_scene(40, 30);
    scene.render.samples = 3;
    scene.render.antialias = Antialias::uniform;
    const World world(scene);
    const RenderResult result = render(world);
    ASSERT_FALSE(result.clamped.empty());
    std::vector<Hit> hits(9);
    PrimaryStats unused;
    int differing = 0;
    for (int y = 0; y < 30; y += 3) {
        for (int x = 0; x < 40; x += 3) {
            grid_hits(world, {}, x, y, hits.data(), unused);
            const GridPixel pixel = shade_grid(world, x, y, hits.data());
            const std::size_t i = static_cast<std::size_t>(y) * 40 + x;
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(result.radiance.rgb[3 * i + c], static_cast<float>(pixel.radiance[c]));
                ASSERT_EQ(result.clamped.rgb[3 * i + c], static_cast<float>(pixel.mean[c]));
                differing += result.radiance.rgb[3 * i + c] != result.clamped.rgb[3 * i + c];
            }
        }
    }
    EXPECT_GT(differing, 0);
}

// The AOVs are the tracer's own answers for each pixel centre's camera ray: its closest hit's t
// and object, and the shading normal World::surface gives it (facing the eye), bit for bit; with
// a sample grid (whose sample (N/2, N/2) is not the centre when N is even) too.
class AovScene : public ::testing::TestWithParam<const char*> {};

TEST_P(AovScene, AovsAreTheTracersHitAtEachPixelCentre) {
    for (const int samples : {1, 2}) {
        Scene scene = shipped(GetParam(), 64, 48);
        scene.render.samples = samples;
        scene.render.antialias = Antialias::uniform;
        const World world(scene);
        PrimaryStats unused;
        PhaseTimes times;
        const RenderResult result = trace_frame(world, {}, unused, {}, times, with_aovs());
        int hits = 0;
        for (int y = 0; y < 48; ++y) {
            for (int x = 0; x < 64; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * 64 + x;
                const Ray ray = world.camera().ray(x, y);
                const Hit hit = world.intersect(ray);
                const std::string at = std::string(GetParam()) + " N=" +
                                       std::to_string(samples) + " (" + std::to_string(x) +
                                       ", " + std::to_string(y) + ")";
                if (!hit.found()) {
                    ASSERT_EQ(result.aovs.id[i], 0u) << at;
                    ASSERT_TRUE(std::isinf(result.aovs.depth[i])) << at;
                    ASSERT_EQ(result.aovs.normal[3 * i], 0.0f) << at;
                    continue;
                }
                ++hits;
                ASSERT_EQ(result.aovs.id[i], hit.object + 1) << at;
                ASSERT_EQ(result.aovs.depth[i], static_cast<float>(hit.t)) << at;
                const Vec3 n = world.surface(ray, hit).shading;
                for (int c = 0; c < 3; ++c) ASSERT_EQ(result.aovs.normal[3 * i + c], n[c]) << at;
            }
        }
        EXPECT_GT(hits, 0) << GetParam();
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, AovScene, ::testing::ValuesIn(kShippedScenes),
                         [](const auto& info) { return std::string(info.param); });

} // namespace
} // namespace glint

namespace glint {
namespace {

// to_byte's truncation of x + 0.5 in double is std::lround's rounding (halves away from zero) of
// 255·c: checked at every float within 4096 ulps of each half step k + 0.5 (where a rounding
// rule shows), and across [0, 1] at a stride, with values outside [0, 1] clamped.
TEST(FloatFrame, ToByteRoundsAsLroundDoes) {
    const auto reference = [](float c) {
        return static_cast<std::uint8_t>(std::lround(255.0f * glm::clamp(c, 0.0f, 1.0f)));
    };
    for (int k = 0; k < 255; ++k) {
        float c = (k + 0.5f) / 255.0f;
        for (int step = 0; step < 4096; ++step) c = std::nextafter(c, 0.0f);
        for (int step = 0; step < 8192; ++step, c = std::nextafter(c, 1.0f))
            ASSERT_EQ(to_byte(c), reference(c)) << c;
    }
    for (float c = -0.5f; c <= 1.5f; c += 1.0f / 65536) ASSERT_EQ(to_byte(c), reference(c)) << c;
    EXPECT_EQ(to_byte(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(to_byte(std::numeric_limits<float>::infinity()), 255);
}

} // namespace
} // namespace glint
