// What the preview can show (key 1–6, V cycles), and how each view colours a pixel. Item buffer
// (false_colour, trace/image_metrics.h, as `glint compare` draws it) and depth come from the GL
// pass at once; the rest are traced, tile by tile (preview/refiner.h).
#pragma once

#include "trace/image.h"
#include "trace/names.h"
#include "trace/primary_hits.h"

#include <array>
#include <cstdint>
#include <string_view>

namespace glint {

// heat and causes: the live image against a reference setting (preview/comparison.h).
enum class View { final, items, depth, normals, difference, reflections, heat, causes };
inline constexpr int kViewCount = 8;

// For --view: "items".
template <> struct EnumNames<View> {
    static constexpr auto names = name_table("final", "items", "depth", "normals", "difference",
                                             "reflections", "heat", "causes");
};

std::string_view view_label(View view); // for people, in the title: "item buffer"
// Whether the refiner traces this view (otherwise it comes whole from the item buffer, or from
// the comparison against a reference).
inline bool is_traced(View view) {
    return view != View::items && view != View::depth && view != View::heat && view != View::causes;
}

using Rgb = std::array<std::uint8_t, 3>;

// A unit normal's components mapped from [−1, 1] to [0, 255].
Rgb normal_colour(glm::vec3 normal);
// A ray tree's depth (reflections and transmissions), 0 (dark blue) … max_depth (yellow) along
// one ramp.
Rgb reflection_colour(int depth, int max_depth);
// The traced colour darkened to a third, or red where the hybrid and the ray primary hits name
// different objects.
Rgb difference_colour(const std::uint8_t* traced, bool differs);

// The item buffer's view depth, near bright, far dark, on a log scale between the nearest and
// farthest drawn depths; nothing drawn is black.
Image depth_image(const IdImage& ids);

} // namespace glint
