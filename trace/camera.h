// The pinhole camera of docs/ARCHITECTURE.md, "Conventions", centred on the eye (world coordinates
// are camera-relative).
#pragma once

#include "trace/bounds.h"
#include "trace/ray.h"
#include "trace/scene.h"

#include <algorithm>
#include <optional>

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

// Pixels [x0, x1] × [y0, y1] of an image (clamped to [−1, width] and [−1, height]; empty when
// x0 > x1 or y0 > y1 once clamped to the image).
struct PixelRect {
    int x0, y0, x1, y1;

    // How many of the image's pixels it covers.
    double area(int width, int height) const {
        const int w = std::min(x1, width - 1) - std::max(x0, 0) + 1;
        const int h = std::min(y1, height - 1) - std::max(y0, 0) + 1;
        return w > 0 && h > 0 ? static_cast<double>(w) * h : 0.0;
    }
};

// A box seen from the camera: its range of view depth (distance along the forward axis), and
// the pixels of a width × height image of the camera's view (the N× grid of samples has N× its
// size) whose centre rays may meet it: the rectangle around its corners' projections, one pixel
// wider on each side for the rounding of the rays' directions (pixel X's ray is that of
// X + 0.5). No rectangle (unbounded) when a corner lies on or behind the eye's plane.
struct ProjectedBounds {
    double near, far;
    std::optional<PixelRect> pixels;
};
inline ProjectedBounds project_bounds(const PinholeCamera& camera, const Bounds& bounds, int width,
                                      int height) {
    const DVec3 r(camera.right_scaled()), u(camera.up_scaled()), f(camera.forward());
    ProjectedBounds out{kInfinity, -kInfinity, std::nullopt};
    double u0 = kInfinity, u1 = -kInfinity, v0 = kInfinity, v1 = -kInfinity;
    for (int corner = 0; corner < 8; ++corner) {
        const DVec3 c(corner & 1 ? bounds.hi.x : bounds.lo.x,
                      corner & 2 ? bounds.hi.y : bounds.lo.y,
                      corner & 4 ? bounds.hi.z : bounds.lo.z);
        const double z = glm::dot(c, f);
        out.near = std::min(out.near, z), out.far = std::max(out.far, z);
        const double pu = width * (1 + glm::dot(c, r) / (glm::dot(r, r) * z)) / 2;
        const double pv = height * (1 - glm::dot(c, u) / (glm::dot(u, u) * z)) / 2;
        u0 = std::min(u0, pu), u1 = std::max(u1, pu), v0 = std::min(v0, pv), v1 = std::max(v1, pv);
    }
    if (!(out.near > 0)) return out;
    const auto clamp = [](double value, int limit) {
        return static_cast<int>(std::clamp(value, -1.0, static_cast<double>(limit)));
    };
    out.pixels =
        PixelRect{clamp(std::ceil(u0 - 0.5) - 1, width), clamp(std::ceil(v0 - 0.5) - 1, height),
                  clamp(std::floor(u1 - 0.5) + 1, width), clamp(std::floor(v1 - 0.5) + 1, height)};
    return out;
}

} // namespace GLINT_PRECISION
} // namespace glint
