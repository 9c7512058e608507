// The preview's camera controls: orbit around look_at, pan, dolly and reset, as changes to the
// scene's Camera (so every change is one new camera, traced exactly like a scene file's).
#pragma once

#include "trace/scene.h"

namespace glint {

class OrbitCamera {
  public:
    explicit OrbitCamera(const Camera& home) : home_(home), camera_(home) {}

    const Camera& camera() const { return camera_; }

    // Turns the eye around look_at: `yaw` degrees about the scene's up axis, `pitch` degrees
    // towards it. The eye stays at least 1° from the up axis, so the view never flips.
    void orbit(double yaw, double pitch);
    // Moves eye and look_at together by (dx, dy) pixels of the image, right and up: the point at
    // look_at's distance follows the cursor.
    void pan(double dx, double dy);
    // Moves the eye towards look_at (steps > 0) or away, 10 % of the distance a step.
    void dolly(double steps);
    void reset();
    // The image size follows the window's framebuffer.
    void resize(int width, int height);

  private:
    Camera home_, camera_;
};

} // namespace glint
