// Axis-aligned boxes: object extents and the nodes of acceleration structures.
#pragma once

#include "trace/math.h"
#include "trace/ray.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace glint {
inline namespace GLINT_PRECISION {

struct Bounds {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    void extend(Vec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void extend(const Bounds& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    Vec3 centre() const { return 0.5_r * (lo + hi); }
    Real area() const { // surface area, for the SAH
        const Vec3 d = glm::max(hi - lo, Vec3(0.0_r));
        return 2.0_r * (d.x * d.y + d.y * d.z + d.z * d.x);
    }
};

// `b` widened on every axis by a few ulps of its largest coordinate (|lo| + |hi| + extent):
// a triangle test's distance errs with the triangle's size, not with the distance, so a flat
// box left unpadded (as a mesh's own box was) or padded along its thin axis alone could leave a
// computed hit outside it, before the box's entry, and pruning against that box then depended
// on the order things were met in (a quad 24 across, 0.0015 from the ray's origin:
// fuzz/seeds/nff/near-quads.nff, tests/accel_test.cpp). An empty box (no point) comes back NaN,
// which no slab test meets, as before.
inline Bounds padded(Bounds b) {
    const Vec3 reach = glm::abs(b.lo) + glm::abs(b.hi) + (b.hi - b.lo);
    const Vec3 pad(std::max({reach.x, reach.y, reach.z}) * (8 * kUnitRoundoff));
    return {b.lo - pad, b.hi + pad};
}

// A ray prepared for many box tests: branch-free slabs. Components of 1/direction that are
// infinite (the ray is parallel to an axis) are replaced by ±1e30, so that a box face in the
// ray's own plane gives 0·1e30 = 0 instead of 0·inf = NaN; beyond that magnitude the products
// overflow to ±inf, as they should.
struct SlabRay {
    Vec3 origin;
    Vec3 inverse_direction;

    explicit SlabRay(const Ray& ray) : origin(ray.origin) {
        for (int a = 0; a < 3; ++a) inverse_direction[a] = reciprocal(ray.direction[a]);
    }

    // 1/d, or ±1e30 where d is ±0: a finite stand-in, so that 0 · it is 0, never NaN.
    static Real reciprocal(Real d) {
        const Real inv = 1.0_r / d;
        return std::isinf(inv) ? std::copysign(1e30_r, inv) : inv;
    }

    // The ray's segment inside b, clipped to [0, t_max]; false when it is empty. Conservative:
    // the far distance is enlarged by 2γ3 (pbrt-v4, Bounds3::IntersectP), so rounding in the
    // slab arithmetic never drops a box the ray touches.
    [[gnu::always_inline]] bool clip(const Bounds& b, Real t_max, Real& t_near, Real& t_far) const {
        const Vec3 t0 = (b.lo - origin) * inverse_direction;
        const Vec3 t1 = (b.hi - origin) * inverse_direction;
        const Vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
        t_near = std::max(std::max(near.x, near.y), std::max(near.z, 0.0_r));
        t_far =
            std::min(std::min(std::min(far.x, far.y), far.z) * (1.0_r + 2.0_r * gamma(3)), t_max);
        return t_near <= t_far;
    }

    // Entry distance into b over [0, t_max], or infinity.
    [[gnu::always_inline]] Real entry(const Bounds& b, Real t_max) const {
        Real t_near, t_far;
        return clip(b, t_max, t_near, t_far) ? t_near : kInfinity;
    }

    bool hits(const Bounds& b, Real t_max) const { return entry(b, t_max) != kInfinity; }
};

} // namespace GLINT_PRECISION
} // namespace glint
