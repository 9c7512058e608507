// Rays and closest hits: the small values that flow through every intersection query.
#pragma once

#include "trace/math.h"

namespace glint {
inline namespace GLINT_PRECISION {

// origin + t·direction. The direction is not required to be unit length: object-space rays
// keep M⁻¹·d unnormalised so that t means the same point in world and object space.
struct Ray {
    Vec3 origin;
    Vec3 direction;
};

// Four rays side by side (structure of arrays), as SIMD kernels produce and read them: lane i
// is ray i. Unset lanes are left unset (a kernel computes all four; its caller uses some).
struct Rays4 {
    alignas(16) Real origin[3][4];
    alignas(16) Real direction[3][4];

    Ray lane(int i) const {
        return {{origin[0][i], origin[1][i], origin[2][i]},
                {direction[0][i], direction[1][i], direction[2][i]}};
    }
};

inline constexpr std::uint32_t kNoObject = std::numeric_limits<std::uint32_t>::max();

// The closest hit found so far. `primitive` is the triangle index within a mesh, or the part of
// an analytic shape (box face, cylinder cap) so that the surface can be rebuilt without guessing.
struct Hit {
    Real t = kInfinity;
    std::uint32_t object = kNoObject;
    std::uint32_t primitive = 0; // the shape's part (ShapeHit::part)
    Real u = 0, v = 0;           // where on it (ShapeHit::u, v): World::surface needs no new test

    bool found() const { return object != kNoObject; }
};

} // namespace GLINT_PRECISION
} // namespace glint
