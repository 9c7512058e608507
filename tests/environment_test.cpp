// Environments (DESIGN §14, docs/SCENES.md "Environments"): read from a Radiance .hdr or an
// OpenEXR file, or built in (studio); named by --environment or a JSON scene's "environment"
// (relative to the scene file); anything else is an error naming the file, exit 2, nothing
// written.
#include "run_glint.h"

#include "io/environment_file.h"
#include "io/error.h"
#include "io/exr.h"
#include "io/load_scene.h"
#include "trace/texture.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

using testing::fresh_dir;
using testing::glint;
using testing::Outcome;
using testing::write;

namespace fs = std::filesystem;

// A Radiance file of 2 × 1 texels, flat (uncompressed) scan lines of RGBE bytes: (1, 0.5, 0.25)
// and (0, 2, 0) (mantissa m and exponent e stand for m · 2^(e − 136)).
std::string two_texel_hdr() {
    std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n";
    for (const unsigned char byte : {128, 64, 32, 129, 0, 128, 0, 130})
        out += static_cast<char>(byte);
    return out;
}

TEST(Environment, AnHdrFileIsReadAsLinearRadianceTopRowFirst) {
    const fs::path dir = fresh_dir("glint_environment");
    write(dir / "sky.hdr", two_texel_hdr());
    const std::shared_ptr<const Environment> e = load_environment("sky.hdr", dir, "--environment");
    ASSERT_EQ(e->width, 2);
    ASSERT_EQ(e->height, 1);
    EXPECT_EQ(std::vector<float>(e->rgb.begin(), e->rgb.end()),
              (std::vector<float>{1, 0.5f, 0.25f, 0, 2, 0}));
    EXPECT_EQ(e->brightest, glm::vec3(1, 2, 0.25f)); // what the cut-off bound reads
}

TEST(Environment, AnExrFileIsReadAsItsRgb) {
    const fs::path dir = fresh_dir("glint_environment");
    FloatImage colour(2, 1);
    colour.set(0, glm::vec3(3, 0.5f, 0)), colour.set(1, glm::vec3(0, 0, 7));
    write_exr(dir / "sky.exr", ExrLayers{&colour});
    const std::shared_ptr<const Environment> e = load_environment("sky.exr", dir, "--environment");
    ASSERT_EQ(e->width, 2);
    EXPECT_EQ(std::vector<float>(e->rgb.begin(), e->rgb.end()),
              (std::vector<float>{3, 0.5f, 0, 0, 0, 7})); // exact in half floats
}

// The studio is neutral (grey everywhere), brighter overhead than underfoot, and its panels
// behind the camera's usual place (+z) are the brightest of it.
TEST(Environment, TheStudioIsANeutralRoomWithLightsBehindTheCamera) {
    const std::shared_ptr<const Environment> s = load_environment("studio", "/", "--environment");
    ASSERT_EQ(s, studio_environment());
    for (std::size_t i = 0; i < s->rgb.size(); i += 3) {
        EXPECT_EQ(s->rgb[i], s->rgb[i + 1]);
        EXPECT_EQ(s->rgb[i], s->rgb[i + 2]);
    }
    const auto at = [&](glm::dvec3 d) { return environment_radiance(*s, glm::normalize(d)).x; };
    EXPECT_GT(at({0, 1, 0}), at({0, -1, 0}));
    EXPECT_GT(at({-0.78, 0.48, 0.62}), 2 * at({0, 0, -1})); // the left panel, behind the camera
}

TEST(Environment, AJsonSceneNamesOneBesideItAndBadOnesAreErrorsNamingTheFile) {
    const fs::path dir = fresh_dir("glint_environment");
    fs::create_directories(dir / "skies");
    write(dir / "skies" / "sky.hdr", two_texel_hdr());
    write(dir / "scene.json", R"({"environment": "skies/sky.hdr"})");
    const Scene scene = load_scene(dir / "scene.json");
    ASSERT_TRUE(scene.environment);
    EXPECT_EQ(scene.environment->width, 2);
    write(dir / "studio.json", R"({"environment": "studio"})");
    EXPECT_EQ(load_scene(dir / "studio.json").environment, studio_environment());
    write(dir / "none.json", R"({"environment": "none"})");
    EXPECT_FALSE(load_scene(dir / "none.json").environment);
    write(dir / "bad.json", R"({"environment": "sky.png"})");
    try {
        load_scene(dir / "bad.json");
        ADD_FAILURE() << "a .png environment loaded";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("bad.json: /environment: "), std::string::npos) << message;
        EXPECT_NE(message.find("sky.png: an environment is an equirectangular .hdr or .exr"),
                  std::string::npos)
            << message;
    }
}

TEST(Environment, TheFlagOverridesTheSceneAndABadFileExitsTwoWritingNothing) {
    const fs::path dir = fresh_dir("glint_environment");
    write(dir / "sky.hdr", two_texel_hdr());
    write(dir / "broken.hdr", "#?RADIANCE\nnot a header\n");
    const std::string scene = std::string(GLINT_SOURCE_DIR) + "/scenes/default.json";
    Outcome r = glint(dir, "render " + scene + " --size 16x12 --environment broken.hdr -o x.png");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--environment: " + (dir / "broken.hdr").string() + ": "),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    r = glint(dir, "render " + scene + " --size 16x12 --environment missing.exr -o x.png");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("missing.exr: no such file"), std::string::npos) << r.err;
    // A readable one changes what the rays that leave the scene return: the image changes.
    r = glint(dir, "render " + scene + " --size 16x12 --environment sky.hdr -o sky.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = glint(dir, "render " + scene + " --size 16x12 --environment none -o none.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = glint(dir, "render " + scene + " --size 16x12 -o plain.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(testing::slurp(dir / "sky.png"), testing::slurp(dir / "plain.png"));
    EXPECT_EQ(testing::slurp(dir / "none.png"), testing::slurp(dir / "plain.png"));
}

// explain names what a ray that left the scene returned: the environment (its radiance in the
// JSON, its name in the text), where the background stood before.
TEST(Environment, ExplainNamesItForARayThatLeaves) {
    const fs::path dir = fresh_dir("glint_environment");
    write(dir / "one.json",
          R"({"camera": {"width": 16, "height": 12}, "objects": [{"shape": "sphere"}]})");
    Outcome r = glint(dir, "explain one.json 0 0 --environment studio --json e.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("leaves the scene into the environment (studio)"), std::string::npos)
        << r.out;
    EXPECT_NE(testing::slurp(dir / "e.json").find("\"environment\""), std::string::npos);
    r = glint(dir, "explain one.json 0 0 --json b.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("hits nothing: the background"), std::string::npos) << r.out;
    EXPECT_EQ(testing::slurp(dir / "b.json").find("\"environment\""), std::string::npos);
}

} // namespace
} // namespace glint
