#include "trace/texture.h"

#include "trace/scene_loader.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace glint {

std::optional<TextureImage> decode_texture(const std::string& bytes, const std::string& name,
                                           std::string& why) {
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), INT32_MAX));
    int width = 0, height = 0, channels = 0;
    // Only what the design names: stb reads more formats, and a model's texture is PNG or JPEG.
    const bool png = bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
    const bool jpeg = bytes.size() >= 3 && bytes.compare(0, 3, "\xff\xd8\xff") == 0;
    if (!png && !jpeg) {
        why = "not a PNG or JPEG image";
        return std::nullopt;
    }
    if (!stbi_info_from_memory(data, size, &width, &height, &channels)) {
        why = std::string("cannot be decoded: ") + stbi_failure_reason();
        return std::nullopt;
    }
    if (width <= 0 || height <= 0 ||
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) > kMaxTexturePixels) {
        why = std::to_string(width) + " × " + std::to_string(height) + " pixels, beyond the " +
              std::to_string(kMaxTexturePixels) + " glint decodes";
        return std::nullopt;
    }
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(data, size, &width, &height, &channels, 3), stbi_image_free);
    if (!pixels) {
        why = std::string("cannot be decoded: ") + stbi_failure_reason();
        return std::nullopt;
    }
    TextureImage image{name, width, height, {}};
    image.rgb.assign(pixels.get(),
                     pixels.get() + static_cast<std::size_t>(width) * height * 3);
    return image;
}

std::optional<TextureImage> load_texture(const std::filesystem::path& path, const std::string& from,
                                         std::vector<std::string>& warnings) {
    std::string why;
    try {
        const std::string bytes = read_scene_file(path, "texture");
        if (auto image = decode_texture(bytes, path.filename().string(), why)) return image;
        why = path.string() + ": " + why;
    } catch (const SceneError& e) {
        why = e.what();
    }
    warnings.push_back(from + ": texture not used: " + printable(why));
    return std::nullopt;
}

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
