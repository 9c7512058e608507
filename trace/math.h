// Vector types, rounding-error constants and the lecture's reflection formula.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>

namespace glint {

using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;
using Mat3 = glm::mat3;
using DMat4 = glm::dmat4;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Largest coordinate or transform entry a scene may use: squares of differences must still be
// finite in float (3.4e38) with room to spare.
inline constexpr double kMaxCoordinate = 1e15;

// Unit roundoff of float (2^-24): one rounded operation has relative error at most this.
inline constexpr float kUnitRoundoff = 0.5f * std::numeric_limits<float>::epsilon();

// gamma(n) bounds the relative error of n consecutive rounded float operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1; pbrt-v4 util/float.h).
constexpr float gamma(int n) {
    return (static_cast<float>(n) * kUnitRoundoff) / (1 - static_cast<float>(n) * kUnitRoundoff);
}

// Perfect reflection of direction d about unit normal n: d' = d - 2n(n·d) (Ray Tracing III).
inline Vec3 reflect(Vec3 d, Vec3 n) {
    return d - 2.0f * n * glm::dot(n, d);
}

inline float max_component(Vec3 v) {
    return glm::max(v.x, glm::max(v.y, v.z));
}

// The bin of a position `bins` bins above the low end of a range cut into `count` bins, clamped
// to [0, count − 1] in float before converting: over a range a few denormals wide, a rounding-
// sized offset is beyond int, and NaN or infinity convert to nothing (the conversion is UB).
inline int bin_index(float bins, int count) {
    if (!(bins > 0)) return 0;
    if (bins >= static_cast<float>(count - 1)) return count - 1;
    return static_cast<int>(bins);
}

} // namespace glint
