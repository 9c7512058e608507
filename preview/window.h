// A GL context with a window (GLFW), for `glint preview`: the same GlContext as the headless
// ones, so the item buffer draws in it unchanged; the window adds a default framebuffer to show
// images in and input to read. One window, one context, used from the thread that made it.
#pragma once

#include "raster/gl_context.h"

struct GLFWwindow;

namespace glint {

// No window system to open a window on (no X display): the message says what GLFW reported.
class NoDisplayError : public GlError {
  public:
    using GlError::GlError;
};

class Window final : public GlContext {
  public:
    // Opens a width×height window (screen coordinates) and makes its 3.3-core context current.
    // `resizable`: whether the user may resize it. Throws NoDisplayError or GlError.
    Window(int width, int height, const char* title, bool resizable);
    ~Window() override;

    GLFWwindow* handle() const { return window_; }
    // The default framebuffer's size in pixels (larger than the window's on high-DPI screens).
    std::pair<int, int> framebuffer_size() const;

  private:
    GLFWwindow* window_ = nullptr;
};

} // namespace glint
