// Base colour textures looked up at a hit (docs/SCENES.md, "Textures"): bilinearly at its texture
// coordinates, with the texture's wrap modes. Files are decoded by io/texture_file.h.
#pragma once

#include "trace/scene.h"

namespace glint {

// What a lookup found: the colour, and where in the image it came from (`glint explain`).
struct TexelSample {
    glm::vec3 colour{1.0f};
    glm::vec2 texel{0.0f}; // continuous texel coordinates of the lookup: (u·width, v·height)
    glm::ivec2 nearest{0}; // the texel whose centre is nearest, after wrapping
};

// The texture's colour at (u, v), bilinear between the four texels around it, each channel
// byte / 255. Coordinates are wrapped per axis by the texture's modes; NaN reads as 0.
TexelSample sample_texture(const Texture& texture, glm::vec2 uv);

// The texture's alpha at (u, v), with the same texels and weights as sample_texture's colour
// (DESIGN §13: the same sampler and filter); 1 where the image has no alpha.
float sample_alpha(const Texture& texture, glm::vec2 uv);

// The environment's radiance in direction d (unit), DESIGN §14: u = 0.5 + atan2(d.x, −d.z)/2π,
// v = acos(d.y)/π, u across and v down the image from its top-left corner, bilinear between
// texel centres, wrapping in u and clamped in v. In double, for both precisions of the tracer.
glm::vec3 environment_radiance(const Environment& environment, glm::dvec3 d);

} // namespace glint
