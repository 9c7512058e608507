// glTF skins and morph targets (DESIGN §14, "Skins and morph targets"): a crafted two-joint skin
// and a two-target morph posed at given times against §14's formula written out again here; the
// shared skinned models move; a sequence's frame is the instant rendered alone; and the bad input
// that exits 2 (a joint beyond the skin, weights all zero or negative), and the weights that are
// renormalized with one warning.
#include "gltf_builder.h"
#include "run_glint.h"

#include "io/error.h"
#include "io/gltf_loader.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

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

constexpr double kTolerance = 1e-5; // float vertices of size ~2: 7 digits leave 1e-6 or better

int ushorts(GltfBuilder& b, const std::vector<std::uint16_t>& values, const char* type, int width) {
    const int v = b.view(values.data(), values.size() * sizeof(std::uint16_t));
    b.doc["accessors"].push_back({{"bufferView", v},
                                  {"componentType", 5123},
                                  {"count", values.size() / static_cast<std::size_t>(width)},
                                  {"type", type}});
    return static_cast<int>(b.doc["accessors"].size() - 1);
}

// A strip of two quads up +Y (x = ±0.5; y = 0, 1, 2), its normals along +X, skinned to two
// joints: J0 at the origin, J1 its child at (0, 1, 0), turned about +Z from 0° at t = 0 to 90° at
// t = 1 (LINEAR). The bottom row follows J0, the middle half each, the top J1. The skinned
// node's own translation (5, 5, 5) must not move it.
struct Strip {
    std::vector<float> xyz = {-0.5f, 0, 0, 0.5f, 0, 0, -0.5f, 1, 0, 0.5f, 1, 0, -0.5f, 2, 0, 0.5f, 2, 0};
    std::vector<float> normals = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
    std::vector<std::uint16_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0,
                                         0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
    std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                                  0.5f, 0.5f, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};

    GltfBuilder build() const {
        GltfBuilder b;
        json primitive = {{"attributes",
                           {{"POSITION", b.floats(xyz, "VEC3", 3)},
                            {"NORMAL", b.floats(normals, "VEC3", 3)},
                            {"JOINTS_0", ushorts(b, joints, "VEC4", 4)},
                            {"WEIGHTS_0", b.floats(weights, "VEC4", 4)}}},
                          {"indices", b.indices({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4})}};
        b.doc["meshes"].push_back({{"primitives", json::array({primitive})}});
        const int j0 = b.node({{"name", "J0"}});
        const int j1 = b.node({{"name", "J1"}, {"translation", {0, 1, 0}}}, false);
        b.doc["nodes"][j0]["children"] = {j1};
        // Inverse bind matrices (column-major): J0's the identity, J1's a move by (0, −1, 0).
        const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
        b.doc["skins"] = json::array({{{"joints", {j0, j1}},
                                       {"inverseBindMatrices", b.floats(ibm, "MAT4", 16)}}});
        b.node({{"mesh", 0}, {"skin", 0}, {"translation", {5, 5, 5}}});
        const double h = std::sqrt(0.5);
        b.doc["animations"] = json::array({{{"samplers",
                                             {{{"input", b.floats({0, 1}, "SCALAR", 1)},
                                               {"output", b.floats({0, 0, 0, 1, 0, 0, float(h), float(h)},
                                                                   "VEC4", 4)}}}},
                                            {"channels",
                                             {{{"sampler", 0},
                                               {"target", {{"node", j1}, {"path", "rotation"}}}}}}}});
        return b;
    }

    // §14's pose of vertex i at time t, written out again: Σ wⱼ · (Jⱼ's world × IBMⱼ) · v, the
    // normal by that sum's inverse transpose.
    std::pair<glm::dvec3, glm::dvec3> pose(std::size_t i, double t) const {
        const double angle = std::numbers::pi / 2 * std::clamp(t, 0.0, 1.0);
        const glm::dmat4 world[2] = {
            glm::dmat4(1.0), glm::rotate(glm::translate(glm::dmat4(1.0), {0, 1, 0}), angle, {0, 0, 1})};
        const glm::dmat4 ibm[2] = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), {0, -1, 0})};
        glm::dmat4 s(0.0);
        for (int k = 0; k < 4; ++k) s += double(weights[4 * i + k]) * (world[joints[4 * i + k]] * ibm[joints[4 * i + k]]);
        const glm::dvec3 v(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        const glm::dvec3 n(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
        return {glm::dvec3(s * glm::dvec4(v, 1)),
                glm::normalize(glm::transpose(glm::inverse(glm::dmat3(s))) * n)};
    }
};

Scene load(const std::string& text, std::optional<double> time) {
    ModelOptions options;
    options.time = time;
    return parse_gltf(text, "crafted.gltf", {}, options);
}

// The one mesh object's mesh.
const TriangleMesh& posed(const Scene& scene) {
    EXPECT_EQ(scene.objects.size(), 1u);
    return scene.meshes.at(scene.objects.at(0).mesh);
}

TEST(Skin, ATwoJointSkinPosesAsTheFormulaSays) {
    const Strip strip;
    const std::string text = strip.build().gltf();
    for (const double t : {0.0, 0.25, 0.5, 0.8, 1.0, 3.0}) {
        const Scene scene = load(text, t);
        const TriangleMesh& mesh = posed(scene);
        EXPECT_EQ(scene.objects[0].transform, DMat4(1.0)) << "the skinned node's own matrix places nothing";
        ASSERT_EQ(mesh.vertices.size(), 6u);
        for (std::size_t i = 0; i < 6; ++i) {
            const auto [p, n] = strip.pose(i, t);
            for (int a = 0; a < 3; ++a) {
                EXPECT_NEAR(mesh.vertices[i][a], p[a], kTolerance) << "t " << t << " vertex " << i;
                EXPECT_NEAR(mesh.normals[i][a], n[a], kTolerance) << "t " << t << " normal " << i;
            }
        }
    }
    // Without --time the skin poses at rest: the joints as the file places them.
    const Scene at_rest = load(text, std::nullopt);
    const TriangleMesh& rest = posed(at_rest);
    for (std::size_t i = 0; i < 6; ++i)
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(rest.vertices[i][a], strip.pose(i, 0).first[a], kTolerance);
}

// One triangle with two morph targets (POSITION and NORMAL), its mesh's weights (0.2, 0.3), a
// node's own weights where given, and an animation of them: LINEAR from (0, 0) at t = 0 to
// (1, 0.5) at t = 2.
GltfBuilder morph(bool node_weights) {
    GltfBuilder b;
    const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::vector<float> normal = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    json primitive = {{"attributes", {{"POSITION", b.floats(xyz, "VEC3", 3)},
                                      {"NORMAL", b.floats(normal, "VEC3", 3)}}},
                      {"indices", b.indices({0, 1, 2})},
                      {"targets",
                       {{{"POSITION", b.floats({0, 0, 1, 0, 0, 0, 0, 0, 0}, "VEC3", 3)},
                         {"NORMAL", b.floats({1, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC3", 3)}},
                        {{"POSITION", b.floats({0, 0, 0, 2, 0, 0, 0, -1, 0}, "VEC3", 3)}}}}};
    b.doc["meshes"].push_back({{"primitives", json::array({primitive})}, {"weights", {0.2, 0.3}}});
    json node = {{"mesh", 0}, {"translation", {0, 0, -1}}};
    if (node_weights) node["weights"] = {0.6, 0.1};
    b.node(node);
    b.doc["animations"] = json::array(
        {{{"samplers", {{{"input", b.floats({0, 2}, "SCALAR", 1)},
                         {"output", b.floats({0, 0, 1, 0.5f}, "SCALAR", 1)}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}});
    return b;
}

// §14's morph written out again: base + Σ wₜ Δₜ, the normal renormalized.
void expect_morphed(const TriangleMesh& mesh, double w0, double w1, const std::string& what) {
    const glm::dvec3 base[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::dvec3 d0[3] = {{0, 0, 1}, {0, 0, 0}, {0, 0, 0}};
    const glm::dvec3 d1[3] = {{0, 0, 0}, {2, 0, 0}, {0, -1, 0}};
    const glm::dvec3 n0 = glm::normalize(glm::dvec3(0, 0, 1) + w0 * glm::dvec3(1, 0, 0));
    for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(mesh.vertices[i][a], (base[i] + w0 * d0[i] + w1 * d1[i])[a], kTolerance)
                << what << " vertex " << i;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(mesh.normals[0][a], n0[a], kTolerance) << what;
}

TEST(Morph, TwoTargetsBlendAsTheFormulaSays) {
    const std::string text = morph(false).gltf();
    expect_morphed(posed(load(text, std::nullopt)), 0.2, 0.3, "at rest, the mesh's weights");
    expect_morphed(posed(load(morph(true).gltf(), std::nullopt)), 0.6, 0.1,
                   "at rest, the node's weights");
    for (const double t : {0.0, 0.5, 1.0, 1.5, 2.0, 5.0}) {
        const double s = std::min(t, 2.0) / 2;
        const Scene scene = load(text, t);
        expect_morphed(posed(scene), s, 0.5 * s, "t " + std::to_string(t));
        EXPECT_EQ(scene.objects[0].transform, translation_matrix({0, 0, -1}))
            << "a morphed node places its mesh";
    }
}

std::string bytes_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// The shared skinned models move: `--time 0` and `--time 1` write different images.
TEST(Skin, TheSharedSkinnedModelsMove) {
    const fs::path dir = testing::fresh_dir("glint_skin_models");
    const fs::path models = fs::path(GLINT_SOURCE_DIR) / "models" / "khronos";
    for (const char* model : {"Fox/glTF/Fox.gltf", "SimpleSkin/glTF/SimpleSkin.gltf",
                              "RiggedSimple/glTF/RiggedSimple.gltf"}) {
        for (const char* t : {"0", "1"}) {
            const Outcome r = glint(dir, "render " + (models / model).string() + " --time " + t +
                                             " --mode ray --size 48x36 -o t" + t + ".png");
            ASSERT_EQ(r.exit_code, 0) << model << "\n" << r.err;
            EXPECT_EQ(r.err.find("skins"), std::string::npos) << "nothing left unused: " << r.err;
        }
        EXPECT_NE(bytes_of(dir / "t0.png"), bytes_of(dir / "t1.png")) << model;
    }
}

// A sequence's frame k is `--time k/F` rendered alone, byte for byte, in both modes: the skinned
// mesh and its structure posed afresh each frame.
TEST(Skin, ASequencesFramesAreTheInstantsRenderedAlone) {
    const fs::path dir = testing::fresh_dir("glint_skin_instants");
    GltfBuilder b = Strip().build();
    b.doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {0, 1, 5}}});
    write(dir / "strip.gltf", b.gltf());
    write(dir / "morph.gltf", [] {
        GltfBuilder m = morph(false);
        m.doc["cameras"].push_back({{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}});
        m.node({{"camera", 0}, {"translation", {0.5, 0.3, 3}}});
        return m.gltf();
    }());
    for (const char* file : {"strip.gltf", "morph.gltf"})
        for (const char* mode : {"ray", "hybrid"}) {
            const std::string common = std::string(" --size 40x30 --mode ") + mode;
            Outcome r = glint(dir, std::string("render ") + file + " --frames 4 --fps 4 -o f-%d.png" + common);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            for (int k = 1; k < 4; ++k) {
                r = glint(dir, std::string("render ") + file + " --time " + std::to_string(k / 4.0) +
                                   " -o t.png" + common);
                ASSERT_EQ(r.exit_code, 0) << r.err;
                EXPECT_EQ(bytes_of(dir / ("f-" + std::to_string(k) + ".png")), bytes_of(dir / "t.png"))
                    << file << " " << mode << " frame " << k;
            }
            EXPECT_NE(bytes_of(dir / "f-0.png"), bytes_of(dir / "f-3.png")) << file << " moves";
        }
}

// Each is refused naming the place; through the command line it exits 2 and writes nothing.
TEST(Skin, BadSkinsAreRefusedNamingThePlace) {
    const auto with = [](auto change) {
        Strip strip;
        change(strip);
        return strip.build().gltf();
    };
    const struct {
        std::string text;
        const char* message;
    } cases[] = {
        {with([](Strip& s) { s.joints[4 * 5] = 2; }),
         "crafted.gltf: /accessors/2: element 5: joint 2 is beyond the skin's 2 joints"},
        {with([](Strip& s) { std::fill_n(s.weights.begin() + 8, 4, 0.0f); }),
         "crafted.gltf: /meshes/0/primitives/0/attributes/WEIGHTS_0: vertex 2: its weights are all zero"},
        {with([](Strip& s) { s.weights[4 * 3 + 1] = -0.5f; }),
         "crafted.gltf: /meshes/0/primitives/0/attributes/WEIGHTS_0: element 3: weights must be "
         "finite and not negative"},
        {[] {
             GltfBuilder b = Strip().build();
             b.doc["skins"][0]["joints"] = {0, 7};
             return b.gltf();
         }(),
         "crafted.gltf: /skins/0/joints/1: no node 7"},
        {[] {
             GltfBuilder b = morph(false);
             b.doc["meshes"][0]["weights"] = {0.5};
             return b.gltf();
         }(),
         "crafted.gltf: /meshes/0/weights: 1 weights for 2 morph targets"},
    };
    for (const auto& c : cases) {
        try {
            load(c.text, 0.5);
            ADD_FAILURE() << "accepted; expected " << c.message;
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
        }
    }
    const fs::path dir = testing::fresh_dir("glint_skin_bad");
    write(dir / "bad.gltf", cases[0].text);
    const Outcome r = glint(dir, "render bad.gltf --time 0.5 --size 20x15 -o out.png");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("joint 2 is beyond the skin's 2 joints"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
}

// Weights that miss 1 by more than the tolerance are divided by their sum, with one warning
// naming the first vertex.
TEST(Skin, WeightsThatMissOneAreRenormalizedWithOneWarning) {
    Strip strip;
    for (std::size_t i = 0; i < strip.weights.size(); ++i) strip.weights[i] *= 1.2f;
    const Scene scene = load(strip.build().gltf(), 0.5);
    int warnings = 0;
    for (const std::string& w : scene.warnings)
        if (w.find("renormalized") != std::string::npos) {
            ++warnings;
            EXPECT_NE(w.find("/meshes/0/primitives/0/attributes/WEIGHTS_0, vertex 0"), std::string::npos) << w;
        }
    EXPECT_EQ(warnings, 1);
    const TriangleMesh& mesh = posed(scene);
    const Strip unscaled;
    for (std::size_t i = 0; i < 6; ++i)
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(mesh.vertices[i][a], unscaled.pose(i, 0.5).first[a], kTolerance);
}

} // namespace
} // namespace glint
