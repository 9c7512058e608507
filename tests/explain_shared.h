// The explain tests' one check, shared by ray mode (explain_test.cpp) and hybrid mode
// (item_buffer_test.cpp): on a rendered frame, explaining pixels gives their bytes, their ray
// counts, and object-space rays that map back through M.
#pragma once

#include "test_scenes.h"

#include "frame/explain.h"
#include "trace/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace glint::testing {

// The pixels a test explains: `count` at random (fixed seed), plus every pixel on an id edge
// (silhouettes) or where a shadow verdict, checker cell or reflected object changes (path keys
// differ from the right or lower neighbour: shadow edges, mirror pixels' edges), up to `count`
// more, spread evenly over the image.
inline std::vector<std::pair<int, int>> pixels_to_explain(const World& world,
                                                          const RenderResult& frame, int count) {
    const int width = world.camera().width(), height = world.camera().height();
    std::vector<std::pair<int, int>> pixels;
    std::mt19937 random(2026);
    for (int k = 0; k < count; ++k)
        pixels.emplace_back(std::uniform_int_distribution<int>(0, width - 1)(random),
                            std::uniform_int_distribution<int>(0, height - 1)(random));
    // Path keys of the one-sample image (trace/shading.h), the adaptive rule's own signal.
    std::vector<std::uint64_t> keys;
    shade_image(world, primary_hits_by_ray(world), {}, &keys);
    std::vector<std::pair<int, int>> edges;
    for (int y = 0; y + 1 < height; ++y)
        for (int x = 0; x + 1 < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (frame.ids[i] != frame.ids[i + 1] || keys[i] != keys[i + 1] ||
                keys[i] != keys[i + width])
                edges.emplace_back(x, y);
        }
    const std::size_t step =
        std::max<std::size_t>(1, edges.size() / static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < edges.size(); k += step) pixels.push_back(edges[k]);
    return pixels;
}

// Explains `pixels` of `frame` (rendered from `world` as `source` says) and checks each against
// it. Returns how many of the explained trees had a reflected or transmitted ray.
inline int expect_explanations_match(const Scene& scene, const World& world,
                                     const PrimarySource& source, const RenderResult& frame,
                                     const std::vector<std::pair<int, int>>& pixels,
                                     const std::string& what) {
    const int width = world.camera().width(), n = world.settings().samples;
    int secondary = 0;
    const Image bytes = frame.bytes();
    for (const auto& [x, y] : pixels) {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        const bool refined = !frame.refined.empty() && frame.refined[i];
        const PixelExplanation e = explain_pixel(world, source, x, y, n / 2, n / 2, refined);
        const std::string at =
            what + " pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")";
        const std::uint8_t* rendered = bytes.pixel(x, y);
        EXPECT_EQ(e.pixel_bytes,
                  (std::array<std::uint8_t, 3>{rendered[0], rendered[1], rendered[2]}))
            << at;
        // The tree's rays are the ones the path counted (one sample: the pixel's own count).
        if (!e.averaged) {
            EXPECT_EQ(e.tree_rays.primary, e.pixel_rays.primary) << at;
            EXPECT_EQ(e.tree_rays.shadow, e.pixel_rays.shadow) << at;
            EXPECT_EQ(e.tree_rays.reflection, e.pixel_rays.reflection) << at;
            EXPECT_EQ(e.tree_rays.transmission, e.pixel_rays.transmission) << at;
        }
        secondary += e.rays.size() > 1;
        // Each object-space ray maps back to the world ray through the scene's M (w = 1 for the
        // origin, w = 0 for the direction). Tolerance: M⁻¹ is stored in float (relative error
        // ~6e-8 per entry) and applied to eye-relative coordinates; 1e-4 of the coordinates'
        // size leaves room for the shipped scenes' condition numbers (below 100) and no more.
        for (std::size_t r = 0; r < e.rays.size(); ++r) {
            if (!e.rays[r].hit.found()) continue;
            const DMat4& m = scene.objects[e.rays[r].hit.object].transform;
            const Ray& local = e.object_rays[r];
            const DVec3 origin = DVec3(m * glm::dvec4(DVec3(local.origin), 1.0));
            const DVec3 direction = DVec3(m * glm::dvec4(DVec3(local.direction), 0.0));
            const DVec3 world_origin = DVec3(e.rays[r].ray.origin) + scene.camera.eye;
            const double size = 1 + glm::length(world_origin) + glm::length(scene.camera.eye);
            EXPECT_LT(glm::length(origin - world_origin), 1e-4 * size) << at << " ray " << r;
            EXPECT_LT(glm::length(direction - DVec3(e.rays[r].ray.direction)), 1e-4)
                << at << " ray " << r;
        }
    }
    return secondary;
}

} // namespace glint::testing
