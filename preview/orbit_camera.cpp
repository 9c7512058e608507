#include "preview/orbit_camera.h"

#include <glm/gtx/rotate_vector.hpp>

#include <algorithm>
#include <cmath>

namespace glint {

void OrbitCamera::orbit(double yaw, double pitch) {
    const DVec3 up = glm::normalize(home_.up);
    DVec3 offset = camera_.eye - camera_.look_at;
    const double distance = glm::length(offset);
    // Pitch first, about the camera's right axis, limited to stay 1°..179° from up.
    const double from_up = std::acos(std::clamp(glm::dot(offset / distance, up), -1.0, 1.0));
    const double target =
        std::clamp(from_up - glm::radians(pitch), glm::radians(1.0), glm::radians(179.0));
    const DVec3 right = glm::cross(offset, up);
    if (glm::length(right) > 0)
        offset = glm::rotate(offset, from_up - target, glm::normalize(right));
    offset = glm::rotate(offset, glm::radians(-yaw), up);
    camera_.eye = camera_.look_at + offset;
    camera_.up = up;
}

void OrbitCamera::pan(double dx, double dy) {
    const DVec3 offset = camera_.eye - camera_.look_at;
    const DVec3 forward = -glm::normalize(offset);
    const DVec3 right = glm::normalize(glm::cross(forward, camera_.up));
    const DVec3 up = glm::cross(right, forward);
    // World units per pixel at look_at's distance.
    const double scale =
        2 * glm::length(offset) * std::tan(glm::radians(camera_.fov_y) / 2) / camera_.height;
    const DVec3 move = (-dx * right - dy * up) * scale;
    camera_.eye += move;
    camera_.look_at += move;
}

void OrbitCamera::dolly(double steps) {
    const DVec3 offset = camera_.eye - camera_.look_at;
    // No closer than a millionth of the home distance: look_at must stay in front of the eye.
    const double home = glm::length(home_.eye - home_.look_at);
    const double distance = std::max(glm::length(offset) * std::pow(0.9, steps), home * 1e-6);
    camera_.eye = camera_.look_at + glm::normalize(offset) * distance;
}

void OrbitCamera::reset() {
    const int width = camera_.width, height = camera_.height;
    camera_ = home_;
    resize(width, height);
}

void OrbitCamera::resize(int width, int height) {
    camera_.width = width;
    camera_.height = height;
}

} // namespace glint
