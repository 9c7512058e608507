// A frame traced in either precision (trace/math.h), through types both share: the double-
// precision tracer is the reference for the float one, in the tests and in `glint tradeoff`.
#pragma once

#include "trace/accel/accel_kind.h"
#include "trace/image.h"
#include "trace/names.h"
#include "trace/scene.h"
#include "trace/tiles.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace glint {

struct RayCounts {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;

    RayCounts& operator+=(const RayCounts& other) {
        primary += other.primary, shadow += other.shadow, reflection += other.reflection;
        return *this;
    }
};

struct RenderResult {
    Image image;
    RayCounts rays;
    // Per pixel (row-major, top row first): the path weight of the reflection ray that
    // max_depth or min_reflectivity kept from being cast, 0 where none was. Perfect reflection
    // makes each pixel's path one chain, so a pixel omits at most one ray (trace/cutoff.h).
    std::vector<float> omitted_weight;
};

// A ray-mode frame (primary rays, then shading), its object ids and its phase times.
struct RayFrame {
    RenderResult result;
    std::vector<std::uint32_t> ids; // per pixel, object index + 1; 0 for background
    double prepare_seconds = 0;     // World: transforms, bounds, acceleration structures
    double primary_seconds = 0;
    double shading_seconds = 0;
};

// The same function in each precision, one per library (glint_trace, glint_trace_f64).
inline namespace f32 {
RayFrame render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                          const TileProgress& progress = {});
}
inline namespace f64 {
RayFrame render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                          const TileProgress& progress = {});
}

enum class Precision { f32, f64 };

template <> struct EnumNames<Precision> {
    static constexpr std::array<std::string_view, 2> names = {"float", "double"};
};

inline RayFrame render_ray_frame(Precision precision, const Scene& scene,
                                 std::optional<AccelKind> accel,
                                 const TileProgress& progress = {}) {
    return precision == Precision::f64 ? f64::render_ray_frame(scene, accel, progress)
                                       : f32::render_ray_frame(scene, accel, progress);
}

} // namespace glint
