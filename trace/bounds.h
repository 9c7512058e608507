// Axis-aligned boxes: object extents and the nodes of acceleration structures.
#pragma once

#include "trace/math.h"
#include "trace/ray.h"

#include <utility>

namespace glint {

struct Bounds {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    void extend(Vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void extend(const Bounds& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    bool empty() const { return lo.x > hi.x; }
    Vec3 centre() const { return 0.5f * (lo + hi); }
    float area() const { // surface area, for the SAH
        const Vec3 d = glm::max(hi - lo, Vec3(0.0f));
        return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

// Slab test of a ray (with precomputed 1/direction) against a box over (0, t_max). Conservative:
// the far distance is enlarged by 2γ3 (pbrt-v4, Bounds3::IntersectP), and NaNs from 0·inf at a
// slab's edge never reject.
inline bool hits_bounds(const Bounds& b, const Ray& ray, Vec3 inverse_direction, float t_max) {
    float t_near = 0.0f, t_far = t_max;
    for (int axis = 0; axis < 3; ++axis) {
        float t0 = (b.lo[axis] - ray.origin[axis]) * inverse_direction[axis];
        float t1 = (b.hi[axis] - ray.origin[axis]) * inverse_direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= 1.0f + 2.0f * gamma(3);
        if (t0 > t_near) t_near = t0;
        if (t1 < t_far) t_far = t1;
        if (t_near > t_far) return false;
    }
    return true;
}

// Entry distance of a ray into a box over [0, t_max], or infinity when it misses; conservative
// like hits_bounds.
inline float entry_distance(const Bounds& b, const Ray& ray, Vec3 inverse_direction, float t_max) {
    float t_near = 0.0f, t_far = t_max;
    for (int axis = 0; axis < 3; ++axis) {
        float t0 = (b.lo[axis] - ray.origin[axis]) * inverse_direction[axis];
        float t1 = (b.hi[axis] - ray.origin[axis]) * inverse_direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= 1.0f + 2.0f * gamma(3);
        if (t0 > t_near) t_near = t0;
        if (t1 < t_far) t_far = t1;
        if (t_near > t_far) return kInfinity;
    }
    return t_near;
}

} // namespace glint
