// Shading exactly per docs/ARCHITECTURE.md's conventions: hand-computed Phong pixels, hard shadows,
// and the two rules that stop recursive reflection (max_depth, min_reflectivity on the path
// weight).
#include "test_scenes.h"

#include "trace/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

TEST(Reflect, MirrorsTheNormalComponentOnly) {
    const Vec3 r = reflect({1, -1, 0}, {0, 1, 0});
    EXPECT_EQ(r, Vec3(1, 1, 0));
    const Vec3 n = glm::normalize(Vec3(1, 1, 0));
    const Vec3 d = glm::normalize(Vec3(0.3f, -0.8f, 0.2f));
    const Vec3 dr = reflect(d, n);
    EXPECT_NEAR(glm::dot(dr, n), -glm::dot(d, n), 1e-6); // angle in = angle out
    EXPECT_NEAR(glm::length(dr - glm::dot(dr, n) * n - (d - glm::dot(d, n) * n)), 0,
                1e-6); // tangent kept
}

// One unit sphere at the origin, one light, camera on the z axis; the 1×1 image's only ray is
// the axis itself, hitting (0, 0, 1) where n = l = v = (0, 0, 1):
// colour = ka·A + L·(kd·1 + ks·1^shininess).
TEST(Shading, OneSphereOneLightGivesTheHandComputedPixel) {
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 1, "height": 1},
        "ambient": [0.5, 0.5, 0.5],
        "lights": [{"position": [0, 0, 10], "color": [0.8, 0.6, 0.4]}],
        "materials": {"m": {"ambient": [0.2, 0.4, 0.6], "diffuse": [0.5, 0.25, 0.125],
                            "specular": [0.2, 0.2, 0.2], "shininess": 7}},
        "objects": [{"shape": "sphere", "material": "m"}]})",
                                    "one-sphere.json");
    const RenderResult r = render(World(scene));
    const double expected[3] = {0.2 * 0.5 + 0.8 * (0.5 + 0.2), 0.4 * 0.5 + 0.6 * (0.25 + 0.2),
                                0.6 * 0.5 + 0.4 * (0.125 + 0.2)};
    for (int c = 0; c < 3; ++c)
        EXPECT_EQ(r.bytes().rgb[c], std::lround(255 * expected[c])) << "channel " << c;
    EXPECT_EQ(r.rays.primary, 1u);
    EXPECT_EQ(r.rays.shadow, 1u);
    EXPECT_EQ(r.rays.reflection, 0u);
}

// The same sphere seen off-axis: every pixel against the conventions evaluated in double.
TEST(Shading, EveryPixelOfALitSphereMatchesTheConventionsInDouble) {
    const int size = 24;
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0.5, 1, 4], "look_at": [0, 0, 0], "fov_y": 40, "width": 24, "height": 24},
        "ambient": [0.1, 0.1, 0.1], "background": [0.2, 0.3, 0.4],
        "lights": [{"position": [3, 4, 5], "color": [0.9, 0.9, 0.9]}],
        "materials": {"m": {"diffuse": [0.7, 0.5, 0.3], "specular": [0.4, 0.4, 0.4], "shininess": 20}},
        "objects": [{"shape": "sphere", "material": "m"}]})",
                                    "lit-sphere.json");
    const RenderResult r = render(World(scene));
    const Image bytes = r.bytes();
    const DVec3 eye(0.5, 1, 4), light(3, 4, 5);
    const DVec3 forward = glm::normalize(-eye);
    const DVec3 right = glm::normalize(glm::cross(forward, DVec3(0, 1, 0)));
    const DVec3 up = glm::cross(right, forward);
    const double h = std::tan(glm::radians(20.0));
    int hits = 0;
    for (int j = 0; j < size; ++j) {
        for (int i = 0; i < size; ++i) {
            const DVec3 d = glm::normalize(forward + (2 * (i + 0.5) / size - 1) * h * right +
                                           (1 - 2 * (j + 0.5) / size) * h * up);
            const double b = glm::dot(eye, d), disc = b * b - (glm::dot(eye, eye) - 1);
            DVec3 colour(0.2, 0.3, 0.4);
            if (disc > 1e-3) { // away from the silhouette
                ++hits;
                const DVec3 p = eye + (-b - std::sqrt(disc)) * d, n = p;
                const DVec3 l = glm::normalize(light - p), v = -d;
                colour = DVec3(0.7, 0.5, 0.3) * 0.1;
                if (glm::dot(n, l) > 0) {
                    const DVec3 refl = 2.0 * n * glm::dot(n, l) - l;
                    colour += 0.9 * (DVec3(0.7, 0.5, 0.3) * glm::dot(n, l) +
                                     0.4 * std::pow(std::max(0.0, glm::dot(refl, v)), 20.0));
                }
            } else if (disc > -1e-3) {
                continue; // silhouette: float and double may disagree on hit or miss
            }
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(bytes.pixel(i, j)[c], 255 * std::clamp(colour[c], 0.0, 1.0),
                            0.5 + 1e-3)
                    << "pixel " << i << "," << j;
        }
    }
    EXPECT_GT(hits, 100);
}

TEST(Shading, AnOccluderBetweenPointAndLightLeavesOnlyAmbient) {
    // The floor point under the camera's central ray is shadowed by a sphere above it.
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 5, 0.001], "look_at": [0, 0, 0], "width": 1, "height": 1},
        "ambient": [0.25, 0.25, 0.25],
        "lights": [{"position": [0, 10, 0]}],
        "materials": {"m": {"diffuse": [0.8, 0.8, 0.8]}},
        "objects": [{"shape": "plane", "material": "m"},
                    {"shape": "sphere", "transform": [{"scale": 0.5}, {"translate": [3, 3, 0]}]}]})",
                                    "shadow.json");
    EXPECT_EQ(render(World(scene)).bytes().rgb[0], std::lround(255 * (0.8 * 0.25 + 0.8)));
    Scene shadowed = scene;
    shadowed.objects[1].transform = translation_matrix({0, 7, 0}) * scale_matrix(DVec3(0.5));
    EXPECT_EQ(render(World(shadowed)).bytes().rgb[0], std::lround(255 * 0.8 * 0.25));
}

TEST(Shading, LightsBehindTheSurfaceCastNoShadowRay) {
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 1, "height": 1},
        "lights": [{"position": [0, 0, -10]}], "objects": [{"shape": "sphere"}]})",
                                    "behind.json");
    const RenderResult r = render(World(scene));
    EXPECT_EQ(r.rays.shadow, 0u);
    EXPECT_EQ(r.bytes().rgb[0], 0);
}

// Two parallel perfect mirrors (y = 0 and y = 2) and a camera between them looking obliquely:
// a primary ray bounces between them for ever unless the rules stop it.
Scene facing_mirrors(float reflectivity, int max_depth, float min_reflectivity) {
    Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 1, 0], "look_at": [1, 0.2, 0], "width": 1, "height": 1},
        "materials": {"mirror": {"diffuse": [0, 0, 0], "reflectivity": 1}},
        "objects": [{"shape": "plane", "material": "mirror"},
                    {"shape": "plane", "material": "mirror", "transform": [{"translate": [0, 2, 0]}]}]})",
                              "mirrors.json");
    scene.materials[1].reflectivity = reflectivity;
    scene.render.max_depth = max_depth;
    scene.render.min_reflectivity = min_reflectivity;
    return scene;
}

TEST(Reflection, RecursionStopsAtMaxDepth) {
    for (int depth : {0, 1, 3, 7, 64})
        EXPECT_EQ(render(World(facing_mirrors(1.0f, depth, 0.0f))).rays.reflection,
                  static_cast<unsigned>(depth));
}

TEST(Reflection, RecursionStopsWhenThePathWeightFallsBelowMinReflectivity) {
    // Path weights 0.5, 0.25, 0.125, 0.0625: three of them reach 0.1.
    EXPECT_EQ(render(World(facing_mirrors(0.5f, 64, 0.1f))).rays.reflection, 3u);
    // A weight equal to the threshold still reflects.
    EXPECT_EQ(render(World(facing_mirrors(0.5f, 64, 0.125f))).rays.reflection, 3u);
    EXPECT_EQ(render(World(facing_mirrors(0.5f, 64, 0.6f))).rays.reflection, 0u);
}

TEST(Reflection, AReflectionRayThatEscapesAddsTheBackground) {
    // A single mirror floor under a camera looking down at 45°: the reflection sees the sky.
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 1, 0], "look_at": [1, 0, 0], "width": 1, "height": 1},
        "background": [0.2, 0.4, 0.6],
        "materials": {"m": {"diffuse": [0, 0, 0], "ambient": [0, 0, 0], "reflectivity": 0.5}},
        "objects": [{"shape": "plane", "material": "m"}]})",
                                    "sky.json");
    const RenderResult r = render(World(scene));
    EXPECT_EQ(r.bytes().rgb[0], std::lround(255 * 0.5 * 0.2));
    EXPECT_EQ(r.bytes().rgb[2], std::lround(255 * 0.5 * 0.6));
}

// A group of pixels' shadow verdicts and the first levels of their ray trees cast ahead in
// packets (TileLighting), through glass too, shade every pixel exactly as its rays cast one at
// a time: the same colour to the bit, the same rays, cut-off weight, depth and path key, with
// 0, 1, 2 and 5 levels cast ahead, on every shipped scene (two with glass), a glass sphere in
// a mirror box whose trees reach kMaxTreeRays, and the same box where the cut-offs stop every
// secondary ray at the primary hit (max_depth 0) or every transmitted one (min_weight above
// the glass's transmission). Each hit cast ahead is the one World::intersect finds for the ray
// shade() casts there, with the same surface; none is cast where shade() casts no ray, or below
// the levels asked for. The whole image is one group, so that most packets are full.
TEST(TileLighting, ShadesEveryPixelExactlyAsItsRaysCastOneAtATime) {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const char* name : testing::kShippedScenes)
        scenes.emplace_back(name, testing::shipped(name, 40, 30));
    const auto mirror_box = [](const char* render) {
        return parse_scene(R"({
        "camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0], "width": 6, "height": 4},
        "lights": [{"position": [0, 2, 1]}, {"position": [0, 0, 0.5]}],
        "materials": {"g": {"reflectivity": 0.5, "transmission": 0.4, "ior": 1.5},
                      "m": {"reflectivity": 1}},
        "render": )" + std::string(render) +
                               R"(,
        "objects": [{"shape": "sphere", "material": "g"},
                    {"shape": "box", "material": "m", "transform": [{"scale": 5}]}]})",
                           "box.json");
    };
    scenes.emplace_back("budget", mirror_box(R"({"max_depth": 64, "min_weight": 0})"));
    scenes.emplace_back("max_depth 0", mirror_box(R"({"max_depth": 0})"));
    scenes.emplace_back("min_weight", mirror_box(R"({"max_depth": 3, "min_weight": 0.45})"));
    for (const int levels : {0, 1, 2, 5}) {
        for (const auto& [name, scene] : scenes) {
            const World world(scene, AccelKind::bvh); // packets: the eight-wide BVH's traversal
            std::vector<Ray> rays;
            std::vector<Hit> hits;
            for (int y = 0; y < world.camera().height(); ++y)
                for (int x = 0; x < world.camera().width(); ++x) {
                    rays.push_back(world.camera().ray(x, y));
                    hits.push_back(world.intersect(rays.back()));
                }
            const TileLighting lighting(world, rays, hits, levels);
            const std::string where = name + ", levels " + std::to_string(levels);
            std::size_t through_glass = 0;  // verdicts that leave shade() glass to follow
            std::size_t ahead_rays[2] = {}; // reflected and transmitted rays cast ahead
            int deepest = 0;
            for (std::size_t k = 0; k < rays.size(); ++k) {
                const CastAhead prepared = lighting.at(k);
                const std::size_t lights = world.lights().size();
                if (lights > 0) {
                    ASSERT_EQ(prepared.node, k);
                    ASSERT_EQ(prepared.lit, rays.size()); // the primary hits'
                    const Real* light = prepared.light + k * lights;
                    through_glass += std::count(light, light + lights, kThroughGlass);
                }
                const PixelSample alone = shade_pixel(world, rays[k], hits[k]);
                const PixelSample ahead = shade_pixel(world, rays[k], hits[k], prepared);
                ASSERT_EQ(ahead.colour, alone.colour) << where << " pixel " << k;
                ASSERT_EQ(ahead.omitted_weight, alone.omitted_weight) << where << " pixel " << k;
                ASSERT_EQ(ahead.path_key, alone.path_key) << where << " pixel " << k;
                ASSERT_EQ(ahead.depth, alone.depth) << where << " pixel " << k;
                ASSERT_EQ(ahead.rays.shadow, alone.rays.shadow) << where << " pixel " << k;
                ASSERT_EQ(ahead.rays.reflection, alone.rays.reflection) << where;
                ASSERT_EQ(ahead.rays.transmission, alone.rays.transmission) << where;
                // The tree cast ahead, walked from the pixel's node: each child's hit and
                // surface are the ones of the ray shade() would cast from its parent, which
                // the tree cast alone then holds (or omits: its weight counts it).
                const auto walk = [&](const auto& self, std::uint32_t n, const Ray& ray,
                                      int depth) -> void {
                    const AheadNode& node = prepared.nodes[n];
                    const SurfacePoint& at = prepared.surfaces[n];
                    deepest = std::max(deepest, depth);
                    const Phong& m = world.material(node.hit.object);
                    const SecondaryRay next[2] = {reflected_ray(ray, at),
                                                  transmitted_ray(ray, at, m.ior)};
                    const Real factor[2] = {m.reflectivity, m.transmission};
                    const std::uint64_t cast[2] = {alone.rays.reflection, alone.rays.transmission};
                    for (int kind = 0; kind < 2; ++kind) {
                        if (node.next[kind] == AheadNode::kNone) {
                            if (factor[kind] > 0 && depth < levels) {
                                ASSERT_GT(alone.omitted_weight, 0) << where << " pixel " << k;
                            }
                            continue;
                        }
                        ASSERT_LT(depth, levels) << where << " pixel " << k;
                        ASSERT_GT(cast[kind], 0u) << where << " pixel " << k;
                        ++ahead_rays[kind];
                        const AheadNode& child = prepared.nodes[node.next[kind]];
                        const SurfacePoint& child_surface = prepared.surfaces[node.next[kind]];
                        const Hit hit = world.intersect(next[kind].ray, kInfinity, next[kind].skip);
                        ASSERT_EQ(child.hit.object, hit.object) << where << " pixel " << k;
                        ASSERT_EQ(child.hit.t, hit.t) << where << " pixel " << k;
                        ASSERT_EQ(child.hit.primitive, hit.primitive) << where << " pixel " << k;
                        if (!hit.found()) continue;
                        const SurfacePoint surface = world.surface(next[kind].ray, hit);
                        ASSERT_EQ(child_surface.position, surface.position) << where;
                        ASSERT_EQ(child_surface.shading, surface.shading) << where;
                        ASSERT_EQ(child_surface.skip, surface.skip) << where;
                        self(self, node.next[kind], next[kind].ray, depth + 1);
                    }
                };
                if (levels == 0) { // the default path keeps no nodes
                    ASSERT_EQ(prepared.nodes, nullptr) << where;
                } else if (hits[k].found()) {
                    walk(walk, static_cast<std::uint32_t>(k), rays[k], 0);
                }
            }
            if (name == "glass" || name == "budget") {
                EXPECT_GT(through_glass, 0u) << where;
            }
            if (levels == 0 || name == "max_depth 0") {
                EXPECT_EQ(ahead_rays[0] + ahead_rays[1], 0u) << where;
                continue;
            }
            if (name == "budget" || name == "min_weight" || name == "mirrors") {
                EXPECT_GT(ahead_rays[0], rays.size() / 2) << where;
            }
            if (name == "budget") {
                EXPECT_GT(ahead_rays[1], 0u) << where;
                EXPECT_EQ(deepest, levels) << where;
            }
            if (name == "min_weight") {
                EXPECT_EQ(ahead_rays[1], 0u) << where;
            }
        }
    }
}

} // namespace
} // namespace glint
