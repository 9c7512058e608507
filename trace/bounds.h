// Axis-aligned boxes: object extents and the nodes of acceleration structures.
#pragma once

#include "trace/math.h"
#include "trace/ray.h"

#include <cmath>
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

// A ray prepared for many box tests: branch-free slabs. Components of 1/direction that are
// infinite (the ray is parallel to an axis) are replaced by ±1e30, so that a box face in the
// ray's own plane gives 0·1e30 = 0 instead of 0·inf = NaN; beyond that magnitude the products
// overflow to ±inf, as they should.
struct SlabRay {
    Vec3 origin;
    Vec3 inverse_direction;

    explicit SlabRay(const Ray& ray) : origin(ray.origin) {
        for (int a = 0; a < 3; ++a) {
            const float inv = 1.0f / ray.direction[a];
            inverse_direction[a] = std::isinf(inv) ? std::copysign(1e30f, inv) : inv;
        }
    }

    // Entry distance into b over [0, t_max], or infinity; the far distance is enlarged by 2γ3
    // as in hits_bounds, so that the test stays conservative.
    float entry(const Bounds& b, float t_max) const {
        const Vec3 t0 = (b.lo - origin) * inverse_direction;
        const Vec3 t1 = (b.hi - origin) * inverse_direction;
        const Vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
        const float t_near = std::max(std::max(near.x, near.y), std::max(near.z, 0.0f));
        const float t_far =
            std::min(std::min(std::min(far.x, far.y), far.z) * (1.0f + 2.0f * gamma(3)), t_max);
        return t_near <= t_far ? t_near : kInfinity;
    }
};

} // namespace glint
