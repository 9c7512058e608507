#include "trace/transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace glint {
inline namespace GLINT_PRECISION {

Transform make_transform(const DMat4& m) {
    Transform t;
    const DMat4 inverse = glm::inverse(m);
    t.linear = Mat3(glm::dmat3(m));
    t.offset = Vec3(DVec3(m[3]));
    t.inverse_linear = Mat3(glm::dmat3(inverse));
    t.inverse_offset = Vec3(DVec3(inverse[3]));

    const Mat3& a = t.linear;
    const bool diagonal = a[0][1] == 0 && a[0][2] == 0 && a[1][0] == 0 && a[1][2] == 0 &&
                          a[2][0] == 0 && a[2][1] == 0;
    const bool uniform = diagonal && a[0][0] == a[1][1] && a[1][1] == a[2][2] && a[0][0] > 0;
    const bool no_offset = t.offset == Vec3(0.0_r);
    if (uniform && a[0][0] == 1.0_r) {
        t.kind = no_offset ? TransformClass::identity : TransformClass::translation;
        // The fast paths use -offset for the inverse: make the general fields agree exactly.
        t.inverse_linear = Mat3(1.0_r);
        t.inverse_offset = -t.offset;
    } else if (uniform) {
        t.kind = TransformClass::uniform_scale;
        t.scale = a[0][0];
        t.inverse_scale = 1.0_r / t.scale;
    } else {
        t.kind = TransformClass::general;
    }

    // Round-trip inconsistency of the two stored float matrices, measured exactly enough in double.
    const glm::dmat3 product = glm::dmat3(t.inverse_linear) * glm::dmat3(t.linear);
    const DVec3 offset_product =
        glm::dmat3(t.inverse_linear) * DVec3(t.offset) + DVec3(t.inverse_offset);
    double linear_error = 0, offset_error = 0;
    for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r)
            linear_error = std::max(linear_error, std::abs(product[c][r] - (c == r ? 1.0 : 0.0)));
        offset_error = std::max(offset_error, std::abs(offset_product[c]));
    }
    // Round up so the float bound is not smaller than the double one.
    t.roundtrip_linear_error = static_cast<Real>(linear_error) * (1 + 2 * kUnitRoundoff);
    t.roundtrip_offset_error = static_cast<Real>(offset_error) * (1 + 2 * kUnitRoundoff);
    return t;
}

Vec3 Transform::point_to_world(Vec3 p) const {
    switch (kind) {
    case TransformClass::identity:
        return p;
    case TransformClass::translation:
        return p + offset;
    case TransformClass::uniform_scale:
        return p * scale + offset;
    case TransformClass::general:
        break;
    }
    return linear * p + offset;
}

Real Transform::normal_stretch(Vec3 n) const {
    switch (kind) {
    case TransformClass::identity:
    case TransformClass::translation:
        return 1.0_r;
    case TransformClass::uniform_scale:
        return inverse_scale;
    case TransformClass::general:
        break;
    }
    return glm::length(glm::transpose(inverse_linear) * n);
}

Vec3 Transform::roundtrip_error(Vec3 p, Vec3 p_error) const {
    // p (in float) lies within p_error of the exact surface. Forward, w = L·p + t rounds with
    // error at most γ3(|L|·|p| + |t|) (pbrt-v4, Transform::ApplyPointWithError); the offset along
    // the normal adds one rounding γ1|w|. Back, M⁻¹·w has the same form with |L⁻¹|, plus the
    // stored float matrices' own inconsistency. Identity maps round only in that final addition.
    const Vec3 abs_p = glm::abs(p);
    if (kind == TransformClass::identity) return p_error + gamma(2) * abs_p;
    // |L| and |L⁻¹| as matrices, or, without rotation or shear, as the scales s and 1/s (s > 0;
    // 1 for a translation): s·I times a finite vector adds only exact zeros to s times it, so the
    // scalar product is the same bound without a matrix's nine products. In camera-relative
    // coordinates most objects are translations: on sombrero-2's mesh this function fell from
    // 2.2% of a frame's samples to 0.3%.
    const auto back_error = [&](const auto& abs_linear, const auto& abs_inverse) {
        const Vec3 world = abs_linear * abs_p + glm::abs(offset);
        const Vec3 world_error = gamma(4) * world;
        return abs_inverse * world_error +
               gamma(3) * (abs_inverse * (world + world_error) + glm::abs(inverse_offset));
    };
    const Vec3 back =
        kind == TransformClass::general
            ? back_error(Mat3(glm::abs(linear[0]), glm::abs(linear[1]), glm::abs(linear[2])),
                         Mat3(glm::abs(inverse_linear[0]), glm::abs(inverse_linear[1]),
                              glm::abs(inverse_linear[2])))
            : back_error(scale, inverse_scale);
    const Real p_sum = abs_p.x + abs_p.y + abs_p.z;
    return p_error + back + Vec3(roundtrip_linear_error * p_sum + roundtrip_offset_error);
}

void ToObjectColumns::assign(std::size_t n) {
    for (std::vector<Real>& column : column_) column.assign(n + 3, 0.0_r);
    column_[kInverseScale].assign(n + 3, 1.0_r);
    general_.assign(n + 3, 0);
}

void ToObjectColumns::set(std::size_t slot, const Transform& transform) {
    Vec3 offset(0.0_r);
    Real inverse_scale = 0.0_r;
    general_[slot] = transform.as_offset_scale(offset, inverse_scale) ? 0 : ~0u;
    for (int axis = 0; axis < 3; ++axis) column_[axis][slot] = offset[axis];
    column_[kInverseScale][slot] = inverse_scale;
    const bool general = general_[slot] != 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            column_[kLinear + 3 * c + r][slot] = general ? transform.inverse_linear[c][r] : 0.0_r;
    for (int r = 0; r < 3; ++r)
        column_[kLinearOffset + r][slot] = general ? transform.inverse_offset[r] : 0.0_r;
}

} // namespace GLINT_PRECISION
} // namespace glint
