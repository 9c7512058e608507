// The acceleration structures by name (docs/ARCHITECTURE.md, "Conventions"), the same for both
// precisions.
#pragma once

#include "trace/names.h"

#include <cstdint>

namespace glint {

enum class AccelKind : std::uint8_t { list, bvh, spheres, grid, kd };

template <> struct EnumNames<AccelKind> {
    static constexpr auto names = name_table("list", "bvh", "spheres", "grid", "kd");
};

} // namespace glint
