#include "preview/views.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

std::string_view view_label(View view) {
    switch (view) {
    case View::final:
        return "final image";
    case View::items:
        return "item buffer";
    case View::depth:
        return "depth";
    case View::normals:
        return "normals";
    case View::difference:
        return "ray vs hybrid";
    case View::reflections:
        return "reflection depth";
    case View::heat:
        return "heat map against the reference";
    case View::causes:
        return "cause map against the reference";
    }
    return "?";
}

Rgb normal_colour(glm::vec3 normal) {
    const glm::vec3 c = normal * 0.5f + 0.5f;
    return {to_byte(c.x), to_byte(c.y), to_byte(c.z)};
}

Rgb reflection_colour(int depth, int max_depth) {
    const float f = max_depth > 0 ? static_cast<float>(depth) / static_cast<float>(max_depth) : 0;
    const glm::vec3 c = glm::mix(glm::vec3(0.05f, 0.05f, 0.4f), glm::vec3(1.0f, 0.9f, 0.1f), f);
    return {to_byte(c.x), to_byte(c.y), to_byte(c.z)};
}

Rgb difference_colour(const std::uint8_t* traced, bool differs) {
    if (differs) return {255, 0, 0};
    return {static_cast<std::uint8_t>(traced[0] / 3), static_cast<std::uint8_t>(traced[1] / 3),
            static_cast<std::uint8_t>(traced[2] / 3)};
}

Image depth_image(const IdImage& ids) {
    float nearest = std::numeric_limits<float>::max(), farthest = 0;
    for (std::size_t i = 0; i < ids.ids.size(); ++i) {
        if (ids.ids[i] == 0 || !std::isfinite(ids.view_depth[i]) || ids.view_depth[i] <= 0)
            continue;
        nearest = std::min(nearest, ids.view_depth[i]);
        farthest = std::max(farthest, ids.view_depth[i]);
    }
    Image image(ids.width, ids.height);
    if (farthest == 0) return image;
    const float span = std::log(farthest / nearest);
    for (std::size_t i = 0; i < ids.ids.size(); ++i) {
        const float d = ids.view_depth[i];
        if (ids.ids[i] == 0 || !std::isfinite(d) || d <= 0) continue;
        const float f = span > 0 ? std::log(d / nearest) / span : 0;
        const std::uint8_t grey = to_byte(1.0f - 0.85f * f);
        std::fill_n(&image.rgb[i * 3], 3, grey);
    }
    return image;
}

} // namespace glint
