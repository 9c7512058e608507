// Affine placements of unit primitives: composed in double, stored in float, classified so that
// intersection skips the work a transform does not need (Ray Tracing III: intersect the
// inversely transformed ray; normals by M⁻ᵀ).
#pragma once

#include "trace/math.h"
#include "trace/ray.h"
#include "trace/scene.h"

#include <cstdint>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

// What a transform does, from cheapest to dearest. Decided on the float values actually stored,
// so a fast path computes exactly what the general path would.
enum class TransformClass : std::uint8_t {
    identity,      // M = I
    translation,   // M = T
    uniform_scale, // M = T·sI with s > 0
    general,       // any invertible affine map
};

// The part of a transform that takes rays to object space, alone: what a BVH leaf keeps of its
// objects beside the shapes' parameters (World's leaf copies), 68 of a Transform's 116 bytes.
struct ToObject {
    TransformClass kind = TransformClass::identity;
    Real inverse_scale = 1.0_r;
    Vec3 offset{0.0_r};         // M's translation
    Mat3 inverse_linear{1.0_r}; // M⁻¹'s 3×3 part
    Vec3 inverse_offset{0.0_r}; // M⁻¹'s translation

    Ray operator()(const Ray& ray) const {
        return apply(kind, inverse_scale, offset, inverse_linear, inverse_offset, ray);
    }
    // The ray in object space: origin with w = 1, direction with w = 0, not renormalised.
    // Inline: every intersection test starts here (Transform's fields or a ToObject's).
    static Ray apply(TransformClass kind, Real inverse_scale, const Vec3& offset,
                     const Mat3& inverse_linear, const Vec3& inverse_offset, const Ray& ray) {
        switch (kind) {
        case TransformClass::identity:
            return ray;
        case TransformClass::translation:
            return {ray.origin - offset, ray.direction};
        case TransformClass::uniform_scale:
            return {(ray.origin - offset) * inverse_scale, ray.direction * inverse_scale};
        case TransformClass::general:
            break;
        }
        return {inverse_linear * ray.origin + inverse_offset, inverse_linear * ray.direction};
    }
};

struct Transform {
    TransformClass kind = TransformClass::identity;
    Mat3 linear{1.0_r};         // M's 3×3 part
    Vec3 offset{0.0_r};         // M's translation
    Mat3 inverse_linear{1.0_r}; // M⁻¹'s 3×3 part
    Vec3 inverse_offset{0.0_r}; // M⁻¹'s translation
    Real scale = 1.0_r;         // s for uniform_scale
    Real inverse_scale = 1.0_r;
    // How far the stored float M⁻¹ and M are from being each other's inverse (max |entry| of
    // M⁻¹M − I, and of M⁻¹·t + t⁻¹), computed in double: part of the spawn-offset bound.
    Real roundtrip_linear_error = 0.0_r;
    Real roundtrip_offset_error = 0.0_r;

    // The ray in object space (ToObject::apply), and the part of the transform it reads.
    Ray to_object(const Ray& ray) const {
        return ToObject::apply(kind, inverse_scale, offset, inverse_linear, inverse_offset, ray);
    }
    ToObject to_object_part() const {
        return {kind, inverse_scale, offset, inverse_linear, inverse_offset};
    }
    // to_object as (p − offset)·inverse_scale (and d·inverse_scale) with the same rounding, for a
    // transform without rotation or shear; false for a general one. Subtracting +0 and
    // multiplying by 1 are exact, so an identity is offset +0 (its stored offset may be −0, and
    // o − (−0) turns a −0 coordinate into +0), scale 1, and a translation scale 1.
    bool as_offset_scale(Vec3& to_offset, Real& to_inverse_scale) const {
        if (kind == TransformClass::general) return false;
        to_offset = kind == TransformClass::identity ? Vec3(0.0_r) : offset;
        to_inverse_scale = kind == TransformClass::uniform_scale ? inverse_scale : 1.0_r;
        return true;
    }
    Vec3 point_to_world(Vec3 p) const;
    // normalize(M⁻ᵀ n) for an object-space normal n.
    // Inline: a call returned the vector split across two registers, which the caller stored
    // and read back as one, a load the store buffer cannot forward (World::surface's largest
    // stall in `perf annotate`).
    Vec3 normal_to_world(Vec3 n) const {
        // Translations and positive uniform scales leave unit normals unchanged.
        if (kind != TransformClass::general) return n;
        return glm::normalize(glm::transpose(inverse_linear) * n);
    }
    // |M⁻ᵀ n| for a unit object-space normal n: how much the transform stretches distances
    // measured along the normal, from world to object space.
    Real normal_stretch(Vec3 n) const;
    // Per-component bound on how far a world point computed as point_to_world(p) (p known to
    // within p_error) lands from p when mapped back by to_object, all in float.
    Vec3 roundtrip_error(Vec3 p, Vec3 p_error) const;
};

// Rounds a validated M (see why_unusable) to float and classifies it.
Transform make_transform(const DMat4& m);

// The ways to object space of a run of objects (a BVH's leaf copies, in slot order) in structure
// of arrays, so that one ray is taken into four objects' spaces at once: to_object4, bit for bit
// each Transform::to_object. A transform without rotation or shear keeps as_offset_scale's
// offset and inverse scale (which a leaf's spheres read directly: sphere_roots4), a general one
// M⁻¹'s entries.
class ToObjectColumns {
  public:
    // n slots, each an identity, with three of padding so that four may be read from any slot.
    void assign(std::size_t n);
    void set(std::size_t slot, const Transform& transform);

    bool general(std::size_t slot) const { return general_[slot] != 0; }
    // as_offset_scale's offset (axis 0–2) and inverse scale, from `slot` on (0 where general).
    const Real* offset(int axis, std::size_t slot) const { return &column_[axis][slot]; }
    const Real* inverse_scale(std::size_t slot) const { return &column_[kInverseScale][slot]; }

    // Lane i: the ray in slot first + i's object space. In SSE both ways are computed four
    // lanes at once, each lane keeping its own, with Transform::to_object's operations in the
    // same order (glm's M⁻¹·p sums its three products left to right); elsewhere, lane by lane.
    void to_object4(const Ray& ray, std::size_t first, Rays4& out) const;

  private:
    // M⁻¹'s 3×3 part column by column (glm's [column][row]), then its translation.
    enum : int { kInverseScale = 3, kLinear = 4, kLinearOffset = 13, kColumns = 16 };
    const Real* at(int column, std::size_t slot) const { return &column_[column][slot]; }
    std::vector<Real> column_[kColumns];
    std::vector<std::uint32_t> general_; // all ones for a general transform: an SSE lane mask
};

inline void ToObjectColumns::to_object4(const Ray& ray, std::size_t first, Rays4& out) const {
#if GLINT_SIMD
    const __m128 general =
        _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&general_[first])));
    const __m128 scale = _mm_loadu_ps(at(kInverseScale, first));
    const __m128 o[3] = {_mm_set1_ps(ray.origin.x), _mm_set1_ps(ray.origin.y),
                         _mm_set1_ps(ray.origin.z)};
    const __m128 d[3] = {_mm_set1_ps(ray.direction.x), _mm_set1_ps(ray.direction.y),
                         _mm_set1_ps(ray.direction.z)};
    const auto pick = [general](__m128 if_general, __m128 otherwise) {
        return _mm_or_ps(_mm_and_ps(general, if_general), _mm_andnot_ps(general, otherwise));
    };
    for (int row = 0; row < 3; ++row) {
        const __m128 m0 = _mm_loadu_ps(at(kLinear + row, first));
        const __m128 m1 = _mm_loadu_ps(at(kLinear + 3 + row, first));
        const __m128 m2 = _mm_loadu_ps(at(kLinear + 6 + row, first));
        const auto times = [&](const __m128(&v)[3]) {
            return _mm_add_ps(_mm_add_ps(_mm_mul_ps(m0, v[0]), _mm_mul_ps(m1, v[1])),
                              _mm_mul_ps(m2, v[2]));
        };
        const __m128 origin =
            pick(_mm_add_ps(times(o), _mm_loadu_ps(at(kLinearOffset + row, first))),
                 _mm_mul_ps(_mm_sub_ps(o[row], _mm_loadu_ps(at(row, first))), scale));
        _mm_store_ps(out.origin[row], origin);
        _mm_store_ps(out.direction[row], pick(times(d), _mm_mul_ps(d[row], scale)));
    }
#else
    for (std::size_t i = 0; i < 4; ++i) {
        const std::size_t slot = first + i;
        Ray local;
        if (general(slot)) {
            Mat3 linear;
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) linear[c][r] = *at(kLinear + 3 * c + r, slot);
            const Vec3 linear_offset(*at(kLinearOffset, slot), *at(kLinearOffset + 1, slot),
                                     *at(kLinearOffset + 2, slot));
            local = {linear * ray.origin + linear_offset, linear * ray.direction};
        } else {
            const Real s = *at(kInverseScale, slot);
            const Vec3 offset(*at(0, slot), *at(1, slot), *at(2, slot));
            local = {(ray.origin - offset) * s, ray.direction * s};
        }
        for (int axis = 0; axis < 3; ++axis) {
            out.origin[axis][i] = local.origin[axis];
            out.direction[axis][i] = local.direction[axis];
        }
    }
#endif
}

} // namespace GLINT_PRECISION
} // namespace glint
