// The pinhole camera of docs/ARCHITECTURE.md, "Conventions", centred on the eye (world coordinates
// are camera-relative).
#pragma once

#include "trace/ray.h"
#include "trace/scene.h"

namespace glint {
inline namespace GLINT_PRECISION {

class PinholeCamera {
  public:
    explicit PinholeCamera(const Camera& camera) : width_(camera.width), height_(camera.height) {
        const DVec3 forward = glm::normalize(camera.look_at - camera.eye);
        const DVec3 right = glm::normalize(glm::cross(forward, camera.up));
        const DVec3 up = glm::cross(right, forward);
        const double h = std::tan(glm::radians(camera.fov_y) / 2);
        const double aspect = static_cast<double>(camera.width) / camera.height;
        forward_ = Vec3(forward);
        right_ = Vec3(right * (h * aspect));
        up_ = Vec3(up * h);
    }

    // The ray through the centre of pixel (i, j), j = 0 the top row; origin at the eye.
    Ray ray(int i, int j) const { return sample_ray(i, j, 0, 0, 1); }

    // Sample (a, b) of pixel (i, j)'s n×n grid (DESIGN §11): i + (a + 0.5)/n in place of
    // i + 0.5, and j + (b + 0.5)/n in place of j + 0.5. (a + 0.5)/n is exactly 0.5 for the
    // centre of an odd grid, so that sample's ray is the pixel centre's, bit for bit.
    Ray sample_ray(int i, int j, int a, int b, int n) const {
        const Real fn = static_cast<Real>(n);
        const Real u = static_cast<Real>(i) + (static_cast<Real>(a) + 0.5_r) / fn;
        const Real v = static_cast<Real>(j) + (static_cast<Real>(b) + 0.5_r) / fn;
        const Real x = 2.0_r * u / static_cast<Real>(width_) - 1.0_r;
        const Real y = 1.0_r - 2.0_r * v / static_cast<Real>(height_);
        return {Vec3(0.0_r), glm::normalize(forward_ + x * right_ + y * up_)};
    }

    Vec3 forward() const { return forward_; }    // unit
    Vec3 right_scaled() const { return right_; } // right · tan(fov_y/2) · aspect
    Vec3 up_scaled() const { return up_; }       // up' · tan(fov_y/2)
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    int width_, height_;
    Vec3 forward_, right_, up_; // right_ and up_ pre-scaled by h·aspect and h
};

} // namespace GLINT_PRECISION
} // namespace glint
