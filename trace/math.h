// The tracer's number type, vector types, rounding-error constants and the lecture's reflection
// formula. The tracer is compiled twice (trace/CMakeLists.txt): in float (glint::f32, the
// default) and in double (glint::f64, the reference), from the same sources; GLINT_DOUBLE picks
// which, and each lives in its own inline namespace so that one program can hold both.
// The tracer's comments say "float" for Real: the default, and the precision whose limits matter.
#pragma once

#include "trace/scene.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

#ifndef GLINT_DOUBLE
#define GLINT_DOUBLE 0
#endif
#if GLINT_DOUBLE
#define GLINT_PRECISION f64
#else
#define GLINT_PRECISION f32
#endif

// The SIMD kernels (the BVH's box tests, a mesh's triangle blocks, a leaf's spheres) are written
// for float with SSE, which every x86-64 processor has; in double, or elsewhere, the same
// arithmetic runs lane by lane.
#if defined(__SSE2__) && !GLINT_DOUBLE
#include <immintrin.h>
#define GLINT_SIMD 1
#else
#define GLINT_SIMD 0
#endif

namespace glint {
inline namespace GLINT_PRECISION {

#if GLINT_DOUBLE
using Real = double;
#else
using Real = float;
#endif

using Vec3 = glm::vec<3, Real>;
using Mat3 = glm::mat<3, 3, Real>;

// A literal in the tracer's precision: 0.5_r is a float in glint::f32 and a double in glint::f64.
constexpr Real operator""_r(long double value) {
    return static_cast<Real>(value);
}
constexpr Real operator""_r(unsigned long long value) {
    return static_cast<Real>(value);
}

inline constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
inline constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

// Unit roundoff (2^-24 in float, 2^-53 in double): one rounded operation has relative error at
// most this.
inline constexpr Real kUnitRoundoff = 0.5_r * std::numeric_limits<Real>::epsilon();

// gamma(n) bounds the relative error of n consecutive rounded operations
// (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1; pbrt-v4 util/float.h).
constexpr Real gamma(int n) {
    return (static_cast<Real>(n) * kUnitRoundoff) / (1 - static_cast<Real>(n) * kUnitRoundoff);
}

// A limit for box tests against a hit distance t, widened for rounding. A box's entry distance
// and a hit's distance are computed by different formulas, so a box holding a hit at exactly t
// may be entered beyond t; pruned against t itself, whether that hit was seen would depend on
// the order a structure visited things in. Found by fuzz_nff: spheres 0.15 across seen from
// 1e15 away (a few ulps; the list and the BVH broke a tie differently); then two overlapping
// coplanar quads 24 across, 0.8 away, whose triangles' distances were 40 ulps from their box's
// entry (a triangle's t errs by about its size over its distance in ulps: pbrt-v4's deltaT), so
// a mesh's box, pruned against the other quad's hit, hid the nearer triangle from the list
// but not from the BVH. 2⁻¹² covers triangles a thousand times larger than their distance.
// What it costs is boxes entered within 0.025% beyond the best hit: with meshes pruning this
// way too, gears-4 (many coplanar triangles) rendered ~4% slower, balls-4 and teapot-12 no
// slower (`glint render … --mode ray --size 1920x1080 --stats s.json`, builds alternated).
inline Real loose(Real t) {
    return t * (1.0_r + 0x1p-12_r);
}

// Perfect reflection of direction d about unit normal n: d' = d - 2n(n·d) (Ray Tracing III).
inline Vec3 reflect(Vec3 d, Vec3 n) {
    return d - 2.0_r * n * glm::dot(n, d);
}

// The transmitted direction for unit direction d at unit normal n facing it, η the ratio of the
// indices (from over to), in Heckbert's form of Snell's law: with c = −n·d and
// k = 1 − η²(1 − c²), η·d + (η·c − √k)·n; when k < 0 (total internal reflection) the mirror
// direction reflect(d, n), and `total` is set.
inline Vec3 refract(Vec3 d, Vec3 n, Real eta, bool& total) {
    const Real c = -glm::dot(n, d);
    const Real k = 1 - eta * eta * (1 - c * c);
    total = k < 0;
    if (total) return reflect(d, n);
    return eta * d + (eta * c - std::sqrt(k)) * n;
}

inline Real max_component(Vec3 v) {
    return glm::max(v.x, glm::max(v.y, v.z));
}

// The bin of a position `bins` bins above the low end of a range cut into `count` bins, clamped
// to [0, count − 1] before converting: over a range a few denormals wide, a rounding-sized
// offset is beyond int, and NaN or infinity convert to nothing (the conversion is UB).
inline int bin_index(Real bins, int count) {
    if (!(bins > 0)) return 0;
    if (bins >= static_cast<Real>(count - 1)) return count - 1;
    return static_cast<int>(bins);
}

} // namespace GLINT_PRECISION
} // namespace glint
