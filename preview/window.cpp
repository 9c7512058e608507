#include "preview/window.h"

#include "preview/glfw_library.h"

#include <glad/gl.h> // before GLFW (GLFW_INCLUDE_NONE: glad provides the GL declarations)

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

namespace glint {
namespace {

// GLFW reports errors through a callback; the latest one becomes the exception's message.
std::string last_error;

void record_error(int, const char* description) {
    last_error = description;
}

} // namespace

Window::Window(int width, int height, const char* title, bool resizable) {
    open_glfw();
    glfwSetErrorCallback(record_error);
    last_error.clear();
    if (!glfwInit()) throw NoDisplayError(last_error.empty() ? "GLFW could not start" : last_error);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, resizable ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_DEPTH_BITS,
                   0); // the item buffer has its own depth; the window shows images
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
    if (!window_) {
        const std::string why = last_error.empty() ? "GLFW could not open a window" : last_error;
        glfwTerminate();
        throw GlError("could not open a " + std::to_string(width) + "x" + std::to_string(height) +
                      " OpenGL 3.3 core window: " + why);
    }
    glfwMakeContextCurrent(window_);
    try {
        // One glad table: loaded here for this context (the preview uses no other).
        load_functions(reinterpret_cast<void* (*)(const char*)>(glfwGetProcAddress));
    } catch (...) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw;
    }
}

Window::~Window() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

std::pair<int, int> Window::framebuffer_size() const {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    return {width, height};
}

} // namespace glint
