// Affine placements of unit primitives: composed in double, stored in float, classified so that
// intersection skips the work a transform does not need (Ray Tracing III: intersect the
// inversely transformed ray; normals by M⁻ᵀ).
#pragma once

#include "trace/math.h"
#include "trace/ray.h"

#include <optional>
#include <string>

namespace glint {

// What a transform does, from cheapest to dearest. Decided on the float values actually stored,
// so a fast path computes exactly what the general path would.
enum class TransformClass : std::uint8_t {
    identity,      // M = I
    translation,   // M = T
    uniform_scale, // M = T·sI with s > 0
    general,       // any invertible affine map
};

// Building blocks of a scene's transform list (column vectors: p' = M·p).
DMat4 translation_matrix(DVec3 offset);
DMat4 scale_matrix(DVec3 factors);
DMat4 rotation_matrix(DVec3 axis, double degrees); // right-handed about the normalised axis

// Largest condition number (after scaling the rows of M⁻¹'s linear part to unit length) that
// glint accepts. Row scaling makes any rotated non-uniform scale perfectly conditioned, since
// float rounds each row of M⁻¹ relative to its own size; what remains measures how nearly
// parallel the rows are (shear). At 1e4, float's 7 digits leave about 3 in object coordinates.
inline constexpr double kMaxConditionNumber = 1e4;

// Why M cannot place an object (singular, non-affine, out of float's range or too ill-conditioned
// to invert in float), or nothing when it can.
std::optional<std::string> why_unusable(const DMat4& m);

struct Transform {
    TransformClass kind = TransformClass::identity;
    Mat3 linear{1.0f};         // M's 3×3 part
    Vec3 offset{0.0f};         // M's translation
    Mat3 inverse_linear{1.0f}; // M⁻¹'s 3×3 part
    Vec3 inverse_offset{0.0f}; // M⁻¹'s translation
    float scale = 1.0f;        // s for uniform_scale
    float inverse_scale = 1.0f;
    // How far the stored float M⁻¹ and M are from being each other's inverse (max |entry| of
    // M⁻¹M − I, and of M⁻¹·t + t⁻¹), computed in double: part of the spawn-offset bound.
    float roundtrip_linear_error = 0.0f;
    float roundtrip_offset_error = 0.0f;

    // The ray in object space: origin with w = 1, direction with w = 0, not renormalised.
    Ray to_object(const Ray& ray) const;
    Vec3 point_to_world(Vec3 p) const;
    // normalize(M⁻ᵀ n) for an object-space normal n.
    Vec3 normal_to_world(Vec3 n) const;
    // |M⁻ᵀ n| for a unit object-space normal n: how much the transform stretches distances
    // measured along the normal, from world to object space.
    float normal_stretch(Vec3 n) const;
    // Per-component bound on how far a world point computed as point_to_world(p) (p known to
    // within p_error) lands from p when mapped back by to_object, all in float.
    Vec3 roundtrip_error(Vec3 p, Vec3 p_error) const;
};

// Rounds a validated M (see why_unusable) to float and classifies it.
Transform make_transform(const DMat4& m);

} // namespace glint
