#include "io/texture_file.h"

#include "io/error.h"
#include "io/read_text.h"

#include <stb_image.h>
#include <webp/decode.h>

#include <algorithm>
#include <cstdint>
#include <memory>

namespace glint {

namespace {

bool too_large(int width, int height, std::string& why) {
    if (width > 0 && height > 0 &&
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) <= kMaxTexturePixels)
        return false;
    why = std::to_string(width) + " × " + std::to_string(height) + " pixels, beyond the " +
          std::to_string(kMaxTexturePixels) + " glint decodes";
    return true;
}

// The image from RGB or RGBA pixels (`channels` 3 or 4), its alpha kept beside the colour.
TextureImage from_pixels(const std::string& name, int width, int height, const std::uint8_t* pixels,
                         int channels) {
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    TextureImage image{name, width, height, {}, {}};
    if (channels == 3) {
        image.rgb.assign(pixels, pixels + count * 3);
        return image;
    }
    image.rgb.resize(count * 3);
    image.alpha.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::copy_n(pixels + 4 * i, 3, &image.rgb[3 * i]);
        image.alpha[i] = pixels[4 * i + 3];
    }
    return image;
}

// A WebP image (glTF's EXT_texture_webp) through libwebp.
std::optional<TextureImage> decode_webp(const std::string& bytes, const std::string& name,
                                        std::string& why) {
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(data, bytes.size(), &features) != VP8_STATUS_OK) {
        why = "cannot be decoded: not a WebP image libwebp reads";
        return std::nullopt;
    }
    if (too_large(features.width, features.height, why)) return std::nullopt;
    int width = 0, height = 0;
    const std::unique_ptr<std::uint8_t, void (*)(void*)> pixels(
        features.has_alpha ? WebPDecodeRGBA(data, bytes.size(), &width, &height)
                           : WebPDecodeRGB(data, bytes.size(), &width, &height),
        WebPFree);
    if (!pixels || width != features.width || height != features.height) {
        why = "cannot be decoded: the WebP data is damaged";
        return std::nullopt;
    }
    return from_pixels(name, width, height, pixels.get(), features.has_alpha ? 4 : 3);
}

} // namespace

std::optional<TextureImage> decode_texture(const std::string& bytes, const std::string& name,
                                           std::string& why) {
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), INT32_MAX));
    int width = 0, height = 0, channels = 0;
    // Only what the design names: stb reads more formats, and a model's texture is PNG, JPEG or
    // WebP (libwebp's).
    const bool png = bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
    const bool jpeg = bytes.size() >= 3 && bytes.compare(0, 3, "\xff\xd8\xff") == 0;
    const bool webp = bytes.size() >= 12 && bytes.compare(0, 4, "RIFF") == 0 &&
                      bytes.compare(8, 4, "WEBP") == 0;
    if (webp) return decode_webp(bytes, name, why);
    if (!png && !jpeg) {
        why = "not a PNG, JPEG or WebP image";
        return std::nullopt;
    }
    if (!stbi_info_from_memory(data, size, &width, &height, &channels)) {
        why = std::string("cannot be decoded: ") + stbi_failure_reason();
        return std::nullopt;
    }
    if (too_large(width, height, why)) return std::nullopt;
    // Two and four channels carry alpha (cut-outs read it); it is kept beside the colour.
    const bool has_alpha = channels == 2 || channels == 4;
    const int wanted = has_alpha ? 4 : 3;
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(data, size, &width, &height, &channels, wanted), stbi_image_free);
    if (!pixels) {
        why = std::string("cannot be decoded: ") + stbi_failure_reason();
        return std::nullopt;
    }
    return from_pixels(name, width, height, pixels.get(), wanted);
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
    warnings.push_back(from + ": texture not used: " + printable(why, std::string::npos));
    return std::nullopt;
}

} // namespace glint
