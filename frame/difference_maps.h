// Pictures of a comparison (frame/difference.h): the heat map of the error and the map of its
// causes, each with its legend drawn below the image in a strip of its own, so that pixel (x, y)
// of a map is pixel (x, y) of the frame (docs/DIFFERENCES.md).
#pragma once

#include "frame/difference.h"
#include "trace/image.h"

#include <array>
#include <cstdint>

namespace glint {

using Rgb = std::array<std::uint8_t, 3>;

// The cause map's colour for a cause (none: the grey of an unchanged pixel is image A's, dimmed).
Rgb cause_colour(Cause cause);

// The heat map's colour for error e of the scale's top value `top`: a perceptual scale (its
// lightness rises evenly), dark blue-violet at 0, yellow at `top` and above.
Rgb heat_colour(double e, double top);

// The top of the heat map's scale for a comparison: the 99th percentile of its pixels' errors
// that are not 0, rounded up to two significant digits (at least 1e-6). Larger errors take the
// top's colour.
double heat_top(const FrameDifference& d);

// The error per pixel on heat_colour's scale, black where it is 0; below it the scale, from 0 to
// its top value, both written (the top with a "+" where larger errors were clipped to it).
Image heat_map(const FrameDifference& d);

// One colour per cause; pixels that do not differ are image A's, grey and dimmed. Below it, each
// cause that occurs with its colour, name and pixel count.
Image cause_map(const FrameDifference& d, const Image& a);

// Both maps at most `width` pixels wide, for a summary: the difference shrunk by a whole factor
// (each block's largest error, and its most frequent cause where any pixel of it differs; A's
// image by its blocks' first pixel), then mapped with legends of their own size (the pixel
// counts stay the full image's).
struct MapThumbnails {
    Image heat, causes;
};
MapThumbnails map_thumbnails(const FrameDifference& d, const Image& a, int width);

// The height of the legend strip a map of this width gets below its image.
int legend_height(int width, int lines);

} // namespace glint
