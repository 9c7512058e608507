// The acceleration structures by name (DESIGN.md §4), the same for both precisions.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace glint {

enum class AccelKind : std::uint8_t { list, bvh, spheres, grid, kd };

inline constexpr std::string_view kAccelNames[] = {"list", "bvh", "spheres", "grid", "kd"};

inline std::string_view accel_name(AccelKind kind) {
    return kAccelNames[static_cast<int>(kind)];
}

inline std::optional<AccelKind> accel_from_name(std::string_view name) {
    for (int k = 0; k < 5; ++k)
        if (kAccelNames[k] == name) return static_cast<AccelKind>(k);
    return std::nullopt;
}

} // namespace glint
