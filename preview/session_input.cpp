// The preview's input (preview/session.h): keys, as H lists them (preview/settings.cpp), and the
// mouse: a drag orbits or pans, the wheel dollies, a click explains the pixel under it.
#include "preview/session.h"

#include "io/error.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace glint {

void Preview::on_key(int key) {
    if (panel_visible_ && panel_->wants_keyboard()) return; // a control of the panel has it
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
        return;
    case GLFW_KEY_H:
        std::cout << kPreviewKeys << std::flush;
        return;
    case GLFW_KEY_P:
        screenshot_requested_ = true;
        return;
    case GLFW_KEY_SPACE:
        playing_ = scene_.animation && !playing_;
        return;
    case GLFW_KEY_G:
        panel_visible_ = !panel_visible_;
        return;
    case GLFW_KEY_R:
        camera_.reset();
        dirty_ = true;
        return;
    case GLFW_KEY_V:
        return set("view", std::string(name_of(static_cast<View>((static_cast<int>(view_) + 1) %
                                                                   kViewCount))));
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET: // within the CLI's limits, as every setting: set() holds them
        return set("depth", std::to_string(std::clamp(
                                scene_.render.max_depth + (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1),
                                0, kMaxDepth)));
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD: { // halving from 1e-4 reaches 0, doubling from 0 starts at 1e-4
        const float cutoff = scene_.render.min_reflectivity;
        return set("cutoff", std::to_string(key == GLFW_KEY_PERIOD
                                                 ? std::min(1.0f, std::max(cutoff * 2, 1e-4f))
                                                 : (cutoff / 2 < 1e-4f ? 0.0f : cutoff / 2)));
    }
    case GLFW_KEY_MINUS:
    case GLFW_KEY_EQUAL:
        return set("tess", std::to_string(std::clamp(key == GLFW_KEY_EQUAL
                                                         ? frame_.tessellation * 2
                                                         : frame_.tessellation / 2,
                                                     kMinTessellation, kMaxTessellation)));
    case GLFW_KEY_M:
        return set("raster",
                   std::string(name_of(static_cast<RasterMode>(
                       (static_cast<int>(frame_.raster) + 1) % all_values<RasterMode>().size()))));
    case GLFW_KEY_E:
        return set("resolve", frame_.resolve == Resolve::exact ? "trust" : "exact");
    case GLFW_KEY_T:
        return set("mode", frame_.mode == Mode::hybrid ? "ray" : "hybrid");
    default:
        if (key < GLFW_KEY_1 || key >= GLFW_KEY_1 + kViewCount) return;
        set("view", std::string(name_of(static_cast<View>(key - GLFW_KEY_1))));
    }
}

// A left press and release without moving is a click: the pixel is explained. Moving more than
// kClickSlop pixels first makes it a drag, which orbits.
constexpr double kClickSlop = 3;

void Preview::on_button(int button, int action) {
    glfwGetCursorPos(window_.handle(), &cursor_x_, &cursor_y_);
    if (action == GLFW_PRESS && panel_visible_ && panel_->wants_mouse()) return; // the panel's
    const bool click = action == GLFW_RELEASE && button_ == GLFW_MOUSE_BUTTON_LEFT && !dragged_;
    button_ = action == GLFW_PRESS ? button : -1;
    if (action == GLFW_PRESS) press_x_ = cursor_x_, press_y_ = cursor_y_, dragged_ = false;
    if (click)
        if (const auto pixel = pixel_at(cursor_x_, cursor_y_)) explain_pending_ = pixel;
}

void Preview::on_cursor(double x, double y) {
    const double dx = x - cursor_x_, dy = y - cursor_y_;
    cursor_x_ = x, cursor_y_ = y;
    if (button_ == GLFW_MOUSE_BUTTON_LEFT && !dragged_ &&
        std::hypot(x - press_x_, y - press_y_) <= kClickSlop)
        return; // still a click
    if (button_ == GLFW_MOUSE_BUTTON_LEFT) {
        dragged_ = true;
        camera_.orbit(0.3 * dx, -0.3 * dy); // degrees per screen pixel
        dirty_ = true;
    } else if (button_ == GLFW_MOUSE_BUTTON_RIGHT || button_ == GLFW_MOUSE_BUTTON_MIDDLE) {
        // Cursor motion is in screen coordinates; the image is in framebuffer pixels.
        int window_width = 1, window_height = 1;
        glfwGetWindowSize(window_.handle(), &window_width, &window_height);
        const double scale =
            static_cast<double>(camera_.camera().width) / std::max(window_width, 1);
        camera_.pan(dx * scale, -dy * scale);
        dirty_ = true;
    }
}

void Preview::on_scroll(double dy) {
    camera_.dolly(dy);
    dirty_ = true;
}

std::optional<std::pair<int, int>> Preview::pixel_at(double x, double y) const {
    if (!job_) return std::nullopt;
    int window_width = 1, window_height = 1;
    glfwGetWindowSize(window_.handle(), &window_width, &window_height);
    const int px = static_cast<int>(std::floor(x * job_->width() / std::max(window_width, 1)));
    const int py = static_cast<int>(std::floor(y * job_->height() / std::max(window_height, 1)));
    if (px < 0 || py < 0 || px >= job_->width() || py >= job_->height()) return std::nullopt;
    return std::pair{px, py};
}

} // namespace glint
