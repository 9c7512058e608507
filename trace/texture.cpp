#include "trace/texture.h"

#include <algorithm>
#include <cmath>

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

} // namespace

TexelSample sample_texture(const Texture& texture, glm::vec2 uv) {
    const TextureImage& image = *texture.image;
    TexelSample s;
    const auto coordinate = [](float c, int n) {
        // Far outside the image only the wrapped position matters; keep the floor exact.
        const double x = std::isfinite(c) ? double(c) * n : 0.0;
        return std::clamp(x, -1e9, 1e9);
    };
    const double x = coordinate(uv.x, image.width), y = coordinate(uv.y, image.height);
    s.texel = {static_cast<float>(x), static_cast<float>(y)};
    // Texel centres sit at half-integers: the four around (x, y) and the weights between them.
    const double fx = std::floor(x - 0.5), fy = std::floor(y - 0.5);
    const float wx = static_cast<float>(x - 0.5 - fx), wy = static_cast<float>(y - 0.5 - fy);
    const int x0 = wrap_index(fx, image.width, texture.wrap_s);
    const int x1 = wrap_index(fx + 1, image.width, texture.wrap_s);
    const int y0 = wrap_index(fy, image.height, texture.wrap_t);
    const int y1 = wrap_index(fy + 1, image.height, texture.wrap_t);
    const auto texel = [&](int tx, int ty) {
        const std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(ty) * image.width + tx) * 3];
        return glm::vec3(p[0], p[1], p[2]) * (1.0f / 255.0f);
    };
    s.colour = (1 - wy) * ((1 - wx) * texel(x0, y0) + wx * texel(x1, y0)) +
               wy * ((1 - wx) * texel(x0, y1) + wx * texel(x1, y1));
    s.nearest = {wx < 0.5f ? x0 : x1, wy < 0.5f ? y0 : y1};
    return s;
}

} // namespace glint
