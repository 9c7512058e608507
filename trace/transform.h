// Affine placements of unit primitives: composed in double, stored in float, classified so that
// intersection skips the work a transform does not need (Ray Tracing III: intersect the
// inversely transformed ray; normals by M⁻ᵀ).
#pragma once

#include "trace/math.h"
#include "trace/ray.h"
#include "trace/scene.h"

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
    Vec3 normal_to_world(Vec3 n) const;
    // |M⁻ᵀ n| for a unit object-space normal n: how much the transform stretches distances
    // measured along the normal, from world to object space.
    Real normal_stretch(Vec3 n) const;
    // Per-component bound on how far a world point computed as point_to_world(p) (p known to
    // within p_error) lands from p when mapped back by to_object, all in float.
    Vec3 roundtrip_error(Vec3 p, Vec3 p_error) const;
};

// Rounds a validated M (see why_unusable) to float and classifies it.
Transform make_transform(const DMat4& m);

} // namespace GLINT_PRECISION
} // namespace glint
