// Triangle meshes that enclose the unit primitives (conservative tessellation): every face plane
// lies at or outside the true surface, so along any ray the mesh is hit no later than the
// surface, which is what the item buffer's exact resolve relies on (trace/primary_hits.cpp).
#pragma once

#include "trace/shapes/mesh.h"

namespace glint {

inline constexpr int kDefaultTessellation = 32;
inline constexpr int kMinTessellation = 3;
inline constexpr int kMaxTessellation = 1024;

struct Tessellation {
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles;
    // Object space: no point of the mesh is farther than this from the true surface.
    float max_deviation = 0.0f;
};

// `level` segments around each curved outline (the sphere gets level/2 latitude bands). For
// sphere, box, disk, cylinder and cone (`open`: without their caps); planes are drawn
// analytically, triangles and meshes as they are.
Tessellation tessellate(ShapeKind shape, float top_radius, int level, bool open = false);

} // namespace glint
