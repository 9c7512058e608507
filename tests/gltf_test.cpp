// glTF node hierarchies (DESIGN §12): a scene of nested TRS and matrix nodes, one mesh placed by
// several of them and a camera on a rotated node, sees exactly the primary hits (ids and depths)
// of the JSON scene written with the composed matrices, in ray and hybrid mode, with every
// acceleration structure. Every transform here is exact in double (rotations by 90° and 180°,
// scales by powers of two, translations in halves), so the two scenes' matrices are equal bit for
// bit whatever order the products are taken in: the test checks the composition (parent · T · R ·
// S, column-major matrices, the camera's −Z), not rounding.
#include "gltf_builder.h"

#include "frame/frame.h"
#include "io/gltf_loader.h"
#include "io/json_loader.h"

#include <set>

#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

namespace glint {
namespace {

using json = nlohmann::json;
using testing::GltfBuilder;

const std::vector<float> kOctahedron = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
const std::vector<std::uint32_t> kOctahedronFaces = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                                      2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
constexpr double kYfov = 0.7;

GltfBuilder hierarchy() {
    GltfBuilder b;
    const int mesh = b.mesh(kOctahedron, kOctahedronFaces);
    // Parent: TRS (translate, 180° about y, scale); children: a matrix node (90° about z, then
    // a translation) and a TRS node; a third placement at the root.
    const int by_matrix = b.node({{"mesh", mesh},
                                  {"matrix", {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0.5, 1, 0, 1}}},
                                 false);
    const int by_trs = b.node({{"mesh", mesh}, {"translation", {-1, 0.5, 0}}, {"scale", {0.5, 0.5, 0.5}}},
                              false);
    b.node({{"translation", {1, 0, -2}},
            {"rotation", {0, 1, 0, 0}},
            {"scale", {2, 1, 0.5}},
            {"children", {by_matrix, by_trs}}});
    b.node({{"mesh", mesh}, {"translation", {0, -2, -1}}});
    // The camera: 180° about y and back along −z, so that its −Z looks along +z at the rest.
    b.doc["cameras"].push_back({{"type", "perspective"},
                                {"perspective", {{"yfov", kYfov}, {"znear", 0.1}}}});
    const int lens = b.node({{"camera", 0}, {"translation", {0, 1, 0}}}, false);
    b.node({{"translation", {0.5, 0, -12}}, {"rotation", {0, 1, 0, 0}}, {"children", {lens}}});
    return b;
}

// The same scene as JSON, its matrices composed here by hand (rows, as the JSON format writes).
Scene composed_json() {
    const DMat4 parent = translation_matrix({1, 0, -2}) * DMat4(glm::dvec4(-1, 0, 0, 0),
                                                                glm::dvec4(0, 1, 0, 0),
                                                                glm::dvec4(0, 0, -1, 0),
                                                                glm::dvec4(0, 0, 0, 1)) *
                         scale_matrix({2, 1, 0.5});
    const DMat4 child_matrix(glm::dvec4(0, 1, 0, 0), glm::dvec4(-1, 0, 0, 0),
                             glm::dvec4(0, 0, 1, 0), glm::dvec4(0.5, 1, 0, 1));
    const DMat4 placements[] = {parent * child_matrix,
                                parent * translation_matrix({-1, 0.5, 0}) * scale_matrix(DVec3(0.5)),
                                translation_matrix({0, -2, -1})};
    json objects = json::array();
    for (const DMat4& m : placements) {
        json rows = json::array();
        for (int r = 0; r < 4; ++r) rows.push_back({m[0][r], m[1][r], m[2][r], m[3][r]});
        json vertices = json::array();
        for (std::size_t i = 0; i < kOctahedron.size(); i += 3)
            vertices.push_back({kOctahedron[i], kOctahedron[i + 1], kOctahedron[i + 2]});
        json indices = json::array();
        for (std::uint32_t k : kOctahedronFaces) indices.push_back(k);
        objects.push_back({{"shape", "mesh"},
                           {"vertices", vertices},
                           {"indices", indices},
                           {"transform", json::array({{{"matrix", rows}}})}});
    }
    // The camera node's world matrix: T(0.5, 0, −12) · R_y(180°) · T(0, 1, 0).
    const DVec3 eye(0.5, 1, -12), forward(0, 0, 1);
    const json camera = {{"eye", {eye.x, eye.y, eye.z}},
                         {"look_at", {eye.x + forward.x, eye.y + forward.y, eye.z + forward.z}},
                         {"up", {0, 1, 0}},
                         {"fov_y", kYfov * (180.0 / std::numbers::pi)},
                         {"width", 96},
                         {"height", 72}};
    return parse_scene(json{{"camera", camera}, {"objects", objects}}.dump(), "composed.json");
}

class GltfHierarchy : public ::testing::TestWithParam<AccelKind> {};

TEST_P(GltfHierarchy, SeesThePrimaryHitsOfTheJsonSceneWithTheComposedMatrices) {
    const GltfBuilder b = hierarchy();
    const Scene json_scene = composed_json();
    for (const std::string& bytes : {b.gltf(), b.glb()}) {
        ModelOptions options;
        options.size = std::pair{96, 72};
        const Scene gltf = parse_gltf(bytes, "nested.gltf", {}, options);
        EXPECT_EQ(gltf.meshes.size(), 1u); // one mesh, placed three times
        ASSERT_EQ(gltf.objects.size(), 3u);
        EXPECT_EQ(gltf.camera, json_scene.camera);
        for (const Mode mode : {Mode::ray, Mode::hybrid}) {
            FrameSettings settings;
            settings.mode = mode;
            settings.aovs = true;
            const RenderResult a = render_frame(gltf, GetParam(), settings).result;
            const RenderResult e = render_frame(json_scene, GetParam(), settings).result;
            std::size_t hits = 0;
            for (std::size_t i = 0; i < a.aovs.id.size(); ++i) {
                ASSERT_EQ(a.aovs.id[i], e.aovs.id[i]) << name_of(mode) << " pixel " << i;
                ASSERT_EQ(a.aovs.depth[i], e.aovs.depth[i]) << name_of(mode) << " pixel " << i;
                hits += a.aovs.id[i] != 0;
            }
            std::set<std::uint32_t> seen(a.aovs.id.begin(), a.aovs.id.end());
            EXPECT_EQ(seen.size(), 4u) << "every placement and the background are in view";
            EXPECT_GT(hits, a.aovs.id.size() / 20);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(EveryAccel, GltfHierarchy,
                         ::testing::ValuesIn(std::vector<AccelKind>{
                             AccelKind::list, AccelKind::bvh, AccelKind::spheres, AccelKind::grid,
                             AccelKind::kd, AccelKind::bvh2}),
                         [](const auto& info) { return std::string(name_of(info.param)); });

} // namespace
} // namespace glint
