// What every unit primitive answers: where a ray first crosses it (object space), and the
// surface there (point projected back onto the surface, outward normal, error bound).
#pragma once

#include "trace/math.h"
#include "trace/ray.h"

namespace glint {
inline namespace GLINT_PRECISION {

struct ShapeHit {
    Real t = kInfinity;
    std::uint32_t part = 0; // box face, cylinder/cone side or cap, triangle index
    // Where on the part, when the surface needs it from the intersection: a triangle's
    // barycentric weights of its vertices 1 and 2 (0 for the other shapes).
    Real u = 0, v = 0;

    bool found() const { return t != kInfinity; }
};

// A point on a unit primitive in object space.
struct SurfaceSample {
    Vec3 point;  // on the surface up to `error`
    Vec3 normal; // unit, outward
    Vec3 error;  // per-component bound on |point − exact surface point|
    // What shading uses when it differs from `normal` (a mesh's interpolated vertex normals,
    // not necessarily unit), else zero.
    Vec3 shading{0.0_r};
};

// The nearer of two candidate hits; on equal t the first wins, keeping results deterministic.
inline ShapeHit closer(ShapeHit a, ShapeHit b) {
    return b.t < a.t ? b : a;
}

// A candidate t counts when it lies in the open interval (0, t_max).
inline ShapeHit candidate(Real t, Real t_max, std::uint32_t part) {
    return (t > 0 && t < t_max) ? ShapeHit{t, part} : ShapeHit{};
}

} // namespace GLINT_PRECISION
} // namespace glint
