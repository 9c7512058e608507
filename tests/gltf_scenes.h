// Small glTF scenes for the GL tests (tests/gltf_materials_gl_test.cpp,
// tests/gltf_extensions_gl_test.cpp): a textured quad, a camera and a light made with
// GltfBuilder, read at 24 × 24, and rendered in both modes with the bytes held equal.
#pragma once

#include "gltf_builder.h"

#include "frame/frame.h"
#include "io/gltf_loader.h"
#include "io/png.h"

#include <gtest/gtest.h>

#include <array>

namespace glint::testing {

using json = nlohmann::json;

// A PNG of one colour, w × h.
inline std::string solid_png(std::uint8_t r, std::uint8_t g, std::uint8_t b, int w = 1, int h = 1) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = r, p[1] = g, p[2] = b;
        }
    return encode_png(image);
}

// A quad from (−1, −1) to (1, 1) in z = 0, counter-clockwise seen from +z unless `reversed`;
// TEXCOORD_0 (0, 0)…(1, 1), and TEXCOORD_1 where `uv1` is given.
inline int quad(GltfBuilder& b, int material, bool reversed = false, const std::vector<float>& uv1 = {}) {
    const std::vector<std::uint32_t> corners = reversed
                                                   ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                                                   : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    const int mesh = b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, corners, material,
                            {0, 1, 1, 1, 1, 0, 0, 0});
    if (!uv1.empty())
        b.doc["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_1"] =
            b.floats(uv1, "VEC2", 2);
    return mesh;
}

// A camera on +z looking down −z at the origin, 5 away.
inline void camera_on_z(GltfBuilder& b) {
    b.doc["cameras"].push_back(
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
}

// One white point light at `at`.
inline void light_at(GltfBuilder& b, std::array<double, 3> at) {
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "point"}, {"intensity", 1.0}}});
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.node({{"translation", at}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

inline Scene read(const GltfBuilder& b, const std::string& name = "made.gltf",
           const ModelFiles& files = {}) {
    ModelOptions options;
    options.size = std::pair{24, 24};
    return parse_gltf(b.gltf(), name, files, options);
}

// Both modes' bytes, asserting they are the same; the ray mode's image.
inline Image both_modes(const Scene& scene) {
    FrameSettings settings;
    settings.mode = Mode::ray;
    const Image ray = render_frame(scene, std::nullopt, settings).result.bytes();
    settings.mode = Mode::hybrid;
    const Image hybrid = render_frame(scene, std::nullopt, settings).result.bytes();
    EXPECT_TRUE(ray.rgb == hybrid.rgb) << "hybrid mode's bytes differ from ray mode's";
    return ray;
}

inline glm::ivec3 centre(const Image& image) {
    const std::uint8_t* p = image.pixel(image.width / 2, image.height / 2);
    return {p[0], p[1], p[2]};
}

} // namespace glint::testing
