// Base colour textures (docs/SCENES.md, "Textures"): images decoded by stb_image, looked up
// bilinearly at a hit's texture coordinates with the texture's wrap modes.
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <optional>
#include <string>

namespace glint {

// The largest texture glint decodes, in pixels (a 8192 × 8192 image: 192 MiB as RGB).
inline constexpr std::size_t kMaxTexturePixels = std::size_t{1} << 26;

// A PNG or JPEG file's bytes (`bytes`, named `name`) as an image, or nothing with `why` set
// ("not a PNG or JPEG image", "8192 × 16384 pixels, beyond the 67108864 glint decodes").
std::optional<TextureImage> decode_texture(const std::string& bytes, const std::string& name,
                                           std::string& why);

// A texture file read and decoded, or nothing with a warning in `warnings` naming `from` (the
// model file and place that names it): a model that only decorates itself with a texture
// renders without it when it cannot be read.
std::optional<TextureImage> load_texture(const std::filesystem::path& path, const std::string& from,
                                         std::vector<std::string>& warnings);

// What a lookup found: the colour, and where in the image it came from (`glint explain`).
struct TexelSample {
    glm::vec3 colour{1.0f};
    glm::vec2 texel{0.0f}; // continuous texel coordinates of the lookup: (u·width, v·height)
    glm::ivec2 nearest{0}; // the texel whose centre is nearest, after wrapping
};

// The texture's colour at (u, v), bilinear between the four texels around it, each channel
// byte / 255. Coordinates are wrapped per axis by the texture's modes; NaN reads as 0.
TexelSample sample_texture(const Texture& texture, glm::vec2 uv);

} // namespace glint
