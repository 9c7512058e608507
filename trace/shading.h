// Whitted shading from Ray Tracing III: Phong ambient + diffuse + specular per point light with
// hard shadows, plus recursive perfect reflection R_p = … + reflectivity_p · R_q.
#pragma once

#include "trace/world.h"

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

// Colour seen along `ray` (unclamped), which has already produced `hit` (maybe none).
// `depth` is the number of reflections before this hit (0 for the primary hit) and `weight` the
// product of the reflectivities along the path so far.
Vec3 shade(const World& world, const Ray& ray, const Hit& hit, int depth, float weight,
           RayCounts& counts);

} // namespace glint
