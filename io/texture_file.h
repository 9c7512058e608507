// Base colour textures from files (docs/SCENES.md, "Textures"): PNG and JPEG images decoded by
// stb_image, WebP by libwebp (glTF's EXT_texture_webp), into the scene's TextureImage; looking
// them up at a hit is the tracer's (trace/texture.h).
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace glint {

// The largest texture glint decodes, in pixels (a 8192 × 8192 image: 192 MiB as RGB).
inline constexpr std::size_t kMaxTexturePixels = std::size_t{1} << 26;

// A PNG, JPEG or WebP file's bytes (`bytes`, named `name`) as an image, or nothing with `why`
// set ("not a PNG, JPEG or WebP image", "8192 × 16384 pixels, beyond the 67108864 glint
// decodes").
std::optional<TextureImage> decode_texture(const std::string& bytes, const std::string& name,
                                           std::string& why);

// A texture file read and decoded, or nothing with a warning in `warnings` naming `from` (the
// model file and place that names it): a model that only decorates itself with a texture
// renders without it when it cannot be read.
std::optional<TextureImage> load_texture(const std::filesystem::path& path, const std::string& from,
                                         std::vector<std::string>& warnings);

} // namespace glint
