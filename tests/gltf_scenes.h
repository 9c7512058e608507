// Small glTF scenes for the GL tests (tests/gltf_materials_gl_test.cpp,
// tests/gltf_extensions_gl_test.cpp, tests/gltf_compression_gl_test.cpp): the models of
// tests/gltf_models.h read at 24 × 24 and rendered in both modes with the bytes held equal.
#pragma once

#include "gltf_models.h"

#include "frame/frame.h"
#include "io/gltf_loader.h"

#include <gtest/gtest.h>

namespace glint::testing {

// The model read at 24 × 24.
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

// The largest difference of one channel between two images of one size.
inline int largest_difference(const Image& a, const Image& b) {
    int most = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) most = std::max(most, std::abs(a.rgb[i] - b.rgb[i]));
    return most;
}

} // namespace glint::testing
