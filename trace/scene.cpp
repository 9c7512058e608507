// What the loader (to check a scene) and World (to place its objects) both need: the transform
// list's building blocks, which transforms can place an object, and object boxes, all in double.
#include "trace/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace glint {

DMat4 translation_matrix(DVec3 offset) {
    return glm::translate(DMat4(1.0), offset);
}

DMat4 scale_matrix(DVec3 factors) {
    return glm::scale(DMat4(1.0), factors);
}

DMat4 rotation_matrix(DVec3 axis, double degrees) {
    return glm::rotate(DMat4(1.0), glm::radians(degrees), glm::normalize(axis));
}

Camera orbit_camera(const Camera& camera, int k, int n) {
    Camera out = camera;
    const DMat4 turn = rotation_matrix({0, 1, 0}, 360.0 * k / n);
    out.eye = camera.look_at + DVec3(turn * glm::dvec4(camera.eye - camera.look_at, 0.0));
    return out;
}

namespace {

// Frobenius norm of a 3×3 matrix.
double frobenius(const glm::dmat3& a) {
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) sum += a[c][r] * a[c][r];
    return std::sqrt(sum);
}

std::string format_double(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

} // namespace

std::optional<std::string> why_unusable(const DMat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return "transform has a non-finite entry";
    // glm is column-major: m[column][row]. The last row must be [0 0 0 1] for an affine map.
    if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1)
        return "transform is not affine (last row must be [0, 0, 0, 1])";
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r)
            if (std::abs(m[c][r]) > kMaxCoordinate)
                return "transform entry " + format_double(m[c][r]) + " is beyond " +
                       format_double(kMaxCoordinate) + ", too large for float";
    const glm::dmat3 linear(m);
    const double det = glm::determinant(linear);
    if (det == 0 || !std::isfinite(det)) return "transform is singular (determinant 0)";
    glm::dmat3 inverse = glm::inverse(linear);
    // Row-equilibrate M⁻¹ (rows are glm's inverse[·][r]) and measure what conditioning is left.
    for (int r = 0; r < 3; ++r) {
        const double norm =
            std::sqrt(inverse[0][r] * inverse[0][r] + inverse[1][r] * inverse[1][r] +
                      inverse[2][r] * inverse[2][r]);
        if (norm < 1 / kMaxCoordinate || norm > kMaxCoordinate)
            return "transform scales by " + format_double(1 / norm) +
                   ", outside what float can invert (1e-15 to 1e15)";
        for (int c = 0; c < 3; ++c) inverse[c][r] /= norm;
    }
    // Frobenius condition number; 3 for a perfectly conditioned matrix, so scale it to 1.
    const double condition = frobenius(inverse) * frobenius(glm::inverse(inverse)) / 3.0;
    if (!(condition <= kMaxConditionNumber))
        return "transform is too close to singular to invert in float (condition number " +
               format_double(condition) + ", limit " + format_double(kMaxConditionNumber) + ")";
    return std::nullopt;
}

std::pair<DVec3, DVec3> transformed_box(const std::pair<DVec3, DVec3>& local, const DMat4& m) {
    const auto& [local_lo, local_hi] = local;
    DVec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int corner = 0; corner < 8; ++corner) {
        const DVec3 p((corner & 1) ? local_hi.x : local_lo.x,
                      (corner & 2) ? local_hi.y : local_lo.y,
                      (corner & 4) ? local_hi.z : local_lo.z);
        const DVec3 w = DVec3(m * glm::dvec4(p, 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    return {lo, hi};
}

} // namespace glint
