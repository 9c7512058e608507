#include "trace/texture.h"

#include "trace/image.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {

namespace {

// Texel index i (any integer, as a double) wrapped into [0, n).
int wrap_index(double i, int n, Wrap mode) {
    switch (mode) {
    case Wrap::clamp: return static_cast<int>(std::clamp(i, 0.0, double(n - 1)));
    case Wrap::repeat: return static_cast<int>(i - n * std::floor(i / n));
    case Wrap::mirror: {
        const int k = static_cast<int>(i - 2.0 * n * std::floor(i / (2.0 * n))); // [0, 2n)
        return k < n ? k : 2 * n - 1 - k;
    }
    }
    return 0;
}

// Where a bilinear lookup at (u, v) reads: the four texels around it (wrapped) and the weights
// between them. Texel centres sit at half-integers.
struct Bilinear {
    double x, y;      // continuous texel coordinates
    int x0, x1, y0, y1;
    float wx, wy;
};

Bilinear bilinear(const Texture& texture, glm::vec2 uv) {
    const TextureImage& image = *texture.image;
    const auto coordinate = [](float c, int n) {
        // Far outside the image only the wrapped position matters; keep the floor exact.
        const double x = std::isfinite(c) ? double(c) * n : 0.0;
        return std::clamp(x, -1e9, 1e9);
    };
    if (texture.uv_transform != glm::mat3(1.0f)) uv = glm::vec2(texture.uv_transform * glm::vec3(uv, 1.0f));
    Bilinear b;
    b.x = coordinate(uv.x, image.width), b.y = coordinate(uv.y, image.height);
    const double fx = std::floor(b.x - 0.5), fy = std::floor(b.y - 0.5);
    b.wx = static_cast<float>(b.x - 0.5 - fx), b.wy = static_cast<float>(b.y - 0.5 - fy);
    b.x0 = wrap_index(fx, image.width, texture.wrap_s);
    b.x1 = wrap_index(fx + 1, image.width, texture.wrap_s);
    b.y0 = wrap_index(fy, image.height, texture.wrap_t);
    b.y1 = wrap_index(fy + 1, image.height, texture.wrap_t);
    return b;
}

} // namespace

TexelSample sample_texture(const Texture& texture, glm::vec2 uv) {
    const TextureImage& image = *texture.image;
    const Bilinear b = bilinear(texture, uv);
    TexelSample s;
    s.texel = {static_cast<float>(b.x), static_cast<float>(b.y)};
    const auto texel = [&](int tx, int ty) {
        const std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(ty) * image.width + tx) * 3];
        if (texture.srgb) return glm::vec3(srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2]));
        return glm::vec3(p[0], p[1], p[2]) * (1.0f / 255.0f);
    };
    s.colour = (1 - b.wy) * ((1 - b.wx) * texel(b.x0, b.y0) + b.wx * texel(b.x1, b.y0)) +
               b.wy * ((1 - b.wx) * texel(b.x0, b.y1) + b.wx * texel(b.x1, b.y1));
    s.nearest = {b.wx < 0.5f ? b.x0 : b.x1, b.wy < 0.5f ? b.y0 : b.y1};
    return s;
}

float sample_alpha(const Texture& texture, glm::vec2 uv) {
    const TextureImage& image = *texture.image;
    if (image.alpha.empty()) return 1.0f;
    const Bilinear b = bilinear(texture, uv);
    const auto texel = [&](int tx, int ty) {
        return image.alpha[static_cast<std::size_t>(ty) * image.width + tx] * (1.0f / 255.0f);
    };
    return (1 - b.wy) * ((1 - b.wx) * texel(b.x0, b.y0) + b.wx * texel(b.x1, b.y0)) +
           b.wy * ((1 - b.wx) * texel(b.x0, b.y1) + b.wx * texel(b.x1, b.y1));
}

glm::vec3 environment_radiance(const Environment& environment, glm::dvec3 d) {
    const int w = environment.width, h = environment.height;
    const double u = 0.5 + std::atan2(d.x, -d.z) / (2 * std::numbers::pi);
    const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / std::numbers::pi;
    // Continuous texel coordinates, centres at half-integers; NaN (a zero direction) reads 0.
    const double x = std::isfinite(u) ? u * w - 0.5 : 0, y = std::isfinite(v) ? v * h - 0.5 : 0;
    const double fx = std::floor(x), fy = std::floor(y);
    const auto wx = static_cast<float>(x - fx), wy = static_cast<float>(y - fy);
    const int x0 = wrap_index(fx, w, Wrap::repeat), x1 = wrap_index(fx + 1, w, Wrap::repeat);
    const int y0 = wrap_index(fy, h, Wrap::clamp), y1 = wrap_index(fy + 1, h, Wrap::clamp);
    const auto texel = [&](int tx, int ty) {
        const float* p = &environment.rgb[(static_cast<std::size_t>(ty) * w + tx) * 3];
        return glm::vec3(p[0], p[1], p[2]);
    };
    return (1 - wy) * ((1 - wx) * texel(x0, y0) + wx * texel(x1, y0)) +
           wy * ((1 - wx) * texel(x0, y1) + wx * texel(x1, y1));
}

} // namespace glint
