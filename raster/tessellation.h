// Triangle meshes that enclose the unit primitives (conservative tessellation), at the level the
// item buffer is asked for: each shape's own `tessellate` (trace/shapes/table.h) does the work.
#pragma once

#include "trace/shapes/table.h"

namespace glint {

inline constexpr int kDefaultTessellation = 32;
inline constexpr int kMinTessellation = 3;
inline constexpr int kMaxTessellation = 1024;

// `level` segments around each curved outline (the sphere gets level/2 latitude bands), clamped
// to [kMinTessellation, kMaxTessellation]. For the tessellated shapes (sphere, box, disk,
// cylinder and cone; `open`: without their caps); empty for the others, which the item buffer
// draws analytically (planes) or as they are (triangles and meshes).
inline Tessellation tessellate(ShapeKind shape, float top_radius, int level, bool open = false) {
    return tessellate_shape(shape, top_radius, open,
                            std::clamp(level, kMinTessellation, kMaxTessellation));
}

} // namespace glint
