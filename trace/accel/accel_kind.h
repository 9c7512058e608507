// The acceleration structures by name (docs/ARCHITECTURE.md, "Conventions"), the same for both
// precisions.
#pragma once

#include "trace/names.h"

#include <cstdint>

namespace glint {

// bvh is the eight-wide SIMD hierarchy (wide_bvh.h); bvh2 the binary one it is collapsed from
// (binary_bvh.h), kept by name as the teaching baseline.
enum class AccelKind : std::uint8_t { list, bvh, spheres, grid, kd, bvh2 };

template <> struct EnumNames<AccelKind> {
    static constexpr auto names = name_table("list", "bvh", "spheres", "grid", "kd", "bvh2");
};

} // namespace glint
