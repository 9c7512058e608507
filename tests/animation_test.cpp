// glTF animations and sequences (DESIGN §13, "Animation time" and "Orbit"): node TRS channels
// interpolated as the glTF 2.0 specification says, held before the first key and after the
// last; `glint render --frames N --orbit` and `--time`; and the bad input that exits 2.
#include "gltf_builder.h"
#include "run_glint.h"

#include "io/error.h"
#include "io/gltf_animation.h"
#include "io/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

namespace glint {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::GltfBuilder;
using testing::glint;
using testing::Outcome;
using testing::write;

// The specification's interpolations written out again, independently of io/gltf_animation.cpp
// (glTF 2.0, Appendix C).
glm::dvec4 spec_slerp(glm::dvec4 a, glm::dvec4 b, double t) {
    const double d = glm::dot(a, b);
    const double angle = std::acos(std::abs(d));
    const double s = d / std::abs(d);
    return std::sin(angle * (1 - t)) / std::sin(angle) * a +
           s * std::sin(angle * t) / std::sin(angle) * b;
}
glm::dvec3 spec_hermite(glm::dvec3 v0, glm::dvec3 b0, glm::dvec3 v1, glm::dvec3 a1, double td,
                        double t) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * v0 + td * (t3 - 2 * t2 + t) * b0 + (-2 * t3 + 3 * t2) * v1 +
           td * (t3 - t2) * a1;
}
glm::dmat4 trs(glm::dvec3 t, glm::dvec4 q, glm::dvec3 s) {
    return trs_matrix({t, q, s});
}

// One node with a triangle, moved by three channels: translation LINEAR over keys at 1, 2, 4 s;
// rotation LINEAR (slerp) over 1 and 3 s; scale CUBICSPLINE over 0 and 2 s. A second node's
// translation is STEP.
GltfBuilder animated() {
    GltfBuilder b;
    const int mesh = b.mesh({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"translation", {5, 0, 0}}});
    const double h = std::sqrt(0.5);
    const int t_in = b.floats({1, 2, 4}, "SCALAR", 1);
    const int t_out = b.floats({0, 0, 0, 2, 0, 0, 2, 4, -2}, "VEC3", 3);
    const int r_in = b.floats({1, 3}, "SCALAR", 1);
    const int r_out = b.floats({0, 0, 0, 1, 0, float(h), 0, float(h)}, "VEC4", 4);
    const int s_in = b.floats({0, 2}, "SCALAR", 1);
    // in-tangent, value, out-tangent per key
    const int s_out = b.floats({0, 0, 0, 1, 1, 1, 1, 0, -1, /**/ 0.5, 0.5, 0.5, 2, 3, 1, 0, 0, 0},
                               "VEC3", 3);
    const int step_in = b.floats({0, 1}, "SCALAR", 1);
    const int step_out = b.floats({5, 0, 0, 5, 3, 0}, "VEC3", 3);
    b.doc["animations"] = json::array(
        {{{"name", "Move"},
          {"samplers",
           {{{"input", t_in}, {"output", t_out}},
            {{"input", r_in}, {"output", r_out}, {"interpolation", "LINEAR"}},
            {{"input", s_in}, {"output", s_out}, {"interpolation", "CUBICSPLINE"}},
            {{"input", step_in}, {"output", step_out}, {"interpolation", "STEP"}}}},
          {"channels",
           {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
            {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}},
            {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}},
            {{"sampler", 3}, {"target", {{"node", 1}, {"path", "translation"}}}}}}}});
    return b;
}

Scene at_time(const GltfBuilder& b, double t, int animation = 0) {
    ModelOptions options;
    options.time = t;
    options.animation = animation;
    return parse_gltf(b.gltf(), "walk.gltf", {}, options);
}

void expect_near(const glm::dmat4& a, const glm::dmat4& b, const std::string& what) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-6) << what << " [" << c << "][" << r << "]";
}

TEST(Animation, NodeTrsAtGivenTimesIsTheSpecificationsInterpolation) {
    const GltfBuilder b = animated();
    const double h = std::sqrt(0.5);
    const glm::dvec4 q0(0, 0, 0, 1), q1(0, h, 0, h);
    for (const double t : {0.0, 0.5, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 7.0}) {
        // Translation: held at 0 before 1 s, then lerp between keys, held after 4 s.
        const glm::dvec3 keys[3] = {{0, 0, 0}, {2, 0, 0}, {2, 4, -2}};
        glm::dvec3 translation = t <= 1 ? keys[0]
                                 : t <= 2 ? glm::mix(keys[0], keys[1], t - 1)
                                 : t <= 4 ? glm::mix(keys[1], keys[2], (t - 2) / 2)
                                          : keys[2];
        const glm::dvec4 rotation = t <= 1 ? q0 : t >= 3 ? q1 : spec_slerp(q0, q1, (t - 1) / 2);
        const glm::dvec3 scale =
            t >= 2 ? glm::dvec3(2, 3, 1)
                   : spec_hermite({1, 1, 1}, {1, 0, -1}, {2, 3, 1}, {0.5, 0.5, 0.5}, 2, t / 2);
        const Scene scene = at_time(b, t);
        ASSERT_EQ(scene.objects.size(), 2u);
        expect_near(scene.objects[0].transform, trs(translation, rotation, scale),
                    "node 0 at t = " + std::to_string(t));
        const glm::dvec3 step = t < 1 ? glm::dvec3(5, 0, 0) : glm::dvec3(5, 3, 0);
        expect_near(scene.objects[1].transform, trs(step, q0, {1, 1, 1}),
                    "node 1 at t = " + std::to_string(t));
        ASSERT_TRUE(scene.animation);
        EXPECT_EQ(scene.animation->name(), "animation 0 (Move)");
        EXPECT_DOUBLE_EQ(scene.animation->duration(), 4.0);
    }
    // A pose computed later from the scene read at 0 is the one read at that time.
    Scene posed = at_time(b, 0);
    posed.animation->pose(posed, 2.5);
    const Scene read = at_time(b, 2.5);
    for (std::size_t i = 0; i < 2; ++i)
        expect_near(posed.objects[i].transform, read.objects[i].transform, "pose " + std::to_string(i));
    // Without --time the nodes are where the file puts them, and no animation is read.
    const Scene still = parse_gltf(b.gltf(), "walk.gltf", {});
    EXPECT_FALSE(still.animation);
    expect_near(still.objects[1].transform, trs({5, 0, 0}, q0, {1, 1, 1}), "still");
}

// The orbit: eight cameras a constant distance from the look-at point, at its height, 45°
// apart about +Y, the first the unorbited camera.
TEST(Animation, OrbitCirclesTheLookAtPointAtAConstantDistance) {
    Camera c;
    c.eye = {1, 2, 5}, c.look_at = {1, 0.5, 0};
    const double distance = glm::length(c.eye - c.look_at);
    for (int k = 0; k < 8; ++k) {
        const Camera o = orbit_camera(c, k, 8);
        EXPECT_EQ(o.look_at, c.look_at);
        EXPECT_EQ(o.up, c.up);
        EXPECT_NEAR(glm::length(o.eye - o.look_at), distance, 1e-12);
        EXPECT_NEAR(o.eye.y, c.eye.y, 1e-12);
        const glm::dvec2 from(c.eye.x - c.look_at.x, c.eye.z - c.look_at.z);
        const glm::dvec2 to(o.eye.x - o.look_at.x, o.eye.z - o.look_at.z);
        const double turned = std::atan2(from.y * to.x - from.x * to.y, glm::dot(from, to));
        const double expected = std::remainder(2 * std::numbers::pi * k / 8, 2 * std::numbers::pi);
        EXPECT_NEAR(std::remainder(turned - expected, 2 * std::numbers::pi), 0, 1e-12) << k;
    }
}

TEST(Animation, FramesAndOrbitWriteOneFileAFrame) {
    const fs::path dir = testing::fresh_dir("glint_animation");
    write(dir / "walk.gltf", animated().gltf());
    Outcome r = glint(dir, "render walk.gltf --frames 8 --orbit --fps 2 --size 40x30 -o f-%02d.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> bytes;
    for (int k = 0; k < 8; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "f-%02d.png", k);
        ASSERT_TRUE(fs::exists(dir / name)) << name;
        std::ifstream in(dir / name, std::ios::binary);
        bytes.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        if (k > 0) {
            EXPECT_NE(bytes[k], bytes[k - 1]) << name;
        }
    }
    EXPECT_NE(r.out.find("frame 8/8 (t = 3.5 s): wrote f-07.png"), std::string::npos) << r.out;
    // --time alone: one frame, the model at that time (ray and hybrid alike).
    r = glint(dir, "render walk.gltf --time 2.5 --size 40x30 --mode ray -o ray.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = glint(dir, "render walk.gltf --time 2.5 --size 40x30 -o hybrid.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream a(dir / "ray.png", std::ios::binary), h(dir / "hybrid.png", std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
              std::string(std::istreambuf_iterator<char>(h), {}));
}

// A sequence's frame k is the one `--time k/F` renders alone, byte for byte, where the file
// brings its camera (a framed model is framed once, at the first frame's pose, so there the
// two differ by the framing alone).
TEST(Animation, ASequencesFramesAreTheInstantsRenderedAlone) {
    const fs::path dir = testing::fresh_dir("glint_animation_instants");
    GltfBuilder b = animated();
    b.doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {2, 2, 14}}});
    write(dir / "walk.gltf", b.gltf());
    for (const char* mode : {"ray", "hybrid"}) {
        const std::string common = std::string(" --size 40x30 --mode ") + mode;
        Outcome r = glint(dir, "render walk.gltf --frames 4 --fps 0.8 -o f-%d.png" + common);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        for (int k = 1; k < 4; ++k) {
            r = glint(dir, "render walk.gltf --time " + std::to_string(k / 0.8) + " -o t.png" + common);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            std::ifstream a(dir / ("f-" + std::to_string(k) + ".png"), std::ios::binary);
            std::ifstream t(dir / "t.png", std::ios::binary);
            EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
                      std::string(std::istreambuf_iterator<char>(t), {}))
                << mode << " frame " << k;
        }
    }
}

// Each exits 2 with the place named, and writes nothing.
TEST(Animation, BadInputExitsTwoAndWritesNothing) {
    const fs::path dir = testing::fresh_dir("glint_animation_bad");
    GltfBuilder unordered = animated();
    unordered.doc["animations"][0]["samplers"][0]["input"] = unordered.floats({1, 3, 2}, "SCALAR", 1);
    write(dir / "unordered.gltf", unordered.gltf());
    GltfBuilder wrong_type = animated();
    wrong_type.doc["animations"][0]["samplers"][1]["output"] = wrong_type.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
    write(dir / "wrong.gltf", wrong_type.gltf());
    write(dir / "walk.gltf", animated().gltf());
    const struct {
        const char* args;
        const char* message;
    } cases[] = {
        {"unordered.gltf --time 1",
         "unordered.gltf: /accessors/10: key times must increase: key 2 (2 s) does not come after "
         "key 1 (3 s)"},
        {"wrong.gltf --time 1",
         "wrong.gltf: /accessors/10/type: is not the type /animations/0/samplers/1/output needs (VEC4)"},
        {"walk.gltf --frames 0 -o f%d.png", "--frames 0: must be 1 or more"},
        {"walk.gltf --frames 3 -o f.png", "-o f.png: --frames 3 needs a number field in the name"},
        {"walk.gltf --frames 3 -o f%s.png", "a sequence's name holds one number field"},
        {"walk.gltf --animation 1 --time 0", "--animation 1: the file has 1 animation(s), 0 to 0"},
        {"walk.gltf --time -1", "--time -1: must be 0 or more seconds"},
        {"walk.gltf --frames 2 --fps 0 -o f%d.png", "--fps 0: must be above 0"},
    };
    for (const auto& c : cases) {
        const std::string args = c.args;
        const Outcome r = glint(dir, "render " + args +
                                         (args.find("-o ") == std::string::npos ? " -o out.png" : "") +
                                         " --size 20x15");
        EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir / "out.png")) << c.args;
        EXPECT_FALSE(fs::exists(dir / "f0.png")) << c.args;
    }
}

} // namespace
} // namespace glint
