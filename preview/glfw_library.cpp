// GLFW opened when the preview first calls it, rather than linked: linked, libglfw and the X11
// libraries it needs (libX11, libxcb, libXau, libXdmcp, libbsd, libmd) loaded at the start of
// every glint process, a ray-mode render's too (docs/PERFORMANCE.md, "GLFW opened only for a
// window"). Each GLFW function the preview and ImGui's GLFW backend call is defined here, with
// the header's signature, and forwards to libglfw.so.3's own, found on first use.
#include "preview/glfw_library.h"

#include "raster/gl_library.h"

#define GLFW_INCLUDE_NONE // no GL header: glad's, where GL is called (DESIGN §6's pitfalls)
#include <GLFW/glfw3.h>

#include <dlfcn.h>

#include <algorithm>
#include <cstddef>
#include <string>

namespace glint {
namespace {

struct Library {
    void* handle = nullptr;
    std::string problem; // why it cannot be used; empty where it can
};

const Library& glfw() {
    static const Library opened = [] {
        Library library;
        try {
            void* handle = open_gl_library({kGlfwLibrary}, "GLFW (libglfw3)");
            decltype(&::glfwInit) init = nullptr; // checked for: a library that is GLFW's
            find_function(handle, init, "glfwInit", kGlfwLibrary);
            library.handle = handle;
        } catch (const GlError& e) {
            library.problem = e.what();
        }
        return library;
    }();
    return opened;
}

// A function's name as a template argument, so that each forwarder keeps its own pointer.
template <std::size_t N> struct Name {
    constexpr Name(const char (&name)[N]) { std::copy_n(name, N, text); }
    char text[N];
};

// Calls libglfw's `kName`, of the header's type `Function`. Without the library (or the name in
// it), does nothing and returns a zero value: no window is made then, open_glfw() having thrown
// first (Window::Window).
template <Name kName, class Function, class... Args> auto call_glfw(Args... args) {
    static const auto function =
        glfw().handle ? reinterpret_cast<Function>(::dlsym(glfw().handle, kName.text)) : nullptr;
    using Result = decltype(function(args...));
    if (!function) return Result();
    return function(args...);
}

} // namespace

void open_glfw() {
    if (!glfw().handle) throw GlError(glfw().problem);
}

} // namespace glint

using glint::call_glfw;

// The preview's (preview/*.cpp).
int glfwInit() {
    return call_glfw<"glfwInit", decltype(&glfwInit)>();
}
void glfwTerminate() {
    call_glfw<"glfwTerminate", decltype(&glfwTerminate)>();
}
GLFWerrorfun glfwSetErrorCallback(GLFWerrorfun callback) {
    return call_glfw<"glfwSetErrorCallback", decltype(&glfwSetErrorCallback)>(callback);
}
void glfwWindowHint(int hint, int value) {
    call_glfw<"glfwWindowHint", decltype(&glfwWindowHint)>(hint, value);
}
GLFWwindow* glfwCreateWindow(int width, int height, const char* title, GLFWmonitor* monitor,
                             GLFWwindow* share) {
    return call_glfw<"glfwCreateWindow", decltype(&glfwCreateWindow)>(width, height, title, monitor,
                                                                      share);
}
void glfwDestroyWindow(GLFWwindow* window) {
    call_glfw<"glfwDestroyWindow", decltype(&glfwDestroyWindow)>(window);
}
void glfwMakeContextCurrent(GLFWwindow* window) {
    call_glfw<"glfwMakeContextCurrent", decltype(&glfwMakeContextCurrent)>(window);
}
GLFWglproc glfwGetProcAddress(const char* name) {
    return call_glfw<"glfwGetProcAddress", decltype(&glfwGetProcAddress)>(name);
}
void glfwSwapInterval(int interval) {
    call_glfw<"glfwSwapInterval", decltype(&glfwSwapInterval)>(interval);
}
void glfwSwapBuffers(GLFWwindow* window) {
    call_glfw<"glfwSwapBuffers", decltype(&glfwSwapBuffers)>(window);
}
int glfwWindowShouldClose(GLFWwindow* window) {
    return call_glfw<"glfwWindowShouldClose", decltype(&glfwWindowShouldClose)>(window);
}
void glfwSetWindowShouldClose(GLFWwindow* window, int value) {
    call_glfw<"glfwSetWindowShouldClose", decltype(&glfwSetWindowShouldClose)>(window, value);
}
void glfwWaitEvents() {
    call_glfw<"glfwWaitEvents", decltype(&glfwWaitEvents)>();
}
void glfwWaitEventsTimeout(double timeout) {
    call_glfw<"glfwWaitEventsTimeout", decltype(&glfwWaitEventsTimeout)>(timeout);
}
void glfwSetWindowUserPointer(GLFWwindow* window, void* pointer) {
    call_glfw<"glfwSetWindowUserPointer", decltype(&glfwSetWindowUserPointer)>(window, pointer);
}
void* glfwGetWindowUserPointer(GLFWwindow* window) {
    return call_glfw<"glfwGetWindowUserPointer", decltype(&glfwGetWindowUserPointer)>(window);
}
void glfwGetWindowSize(GLFWwindow* window, int* width, int* height) {
    call_glfw<"glfwGetWindowSize", decltype(&glfwGetWindowSize)>(window, width, height);
}
void glfwGetFramebufferSize(GLFWwindow* window, int* width, int* height) {
    call_glfw<"glfwGetFramebufferSize", decltype(&glfwGetFramebufferSize)>(window, width, height);
}
void glfwGetCursorPos(GLFWwindow* window, double* x, double* y) {
    call_glfw<"glfwGetCursorPos", decltype(&glfwGetCursorPos)>(window, x, y);
}
GLFWkeyfun glfwSetKeyCallback(GLFWwindow* window, GLFWkeyfun callback) {
    return call_glfw<"glfwSetKeyCallback", decltype(&glfwSetKeyCallback)>(window, callback);
}
GLFWcursorposfun glfwSetCursorPosCallback(GLFWwindow* window, GLFWcursorposfun callback) {
    return call_glfw<"glfwSetCursorPosCallback", decltype(&glfwSetCursorPosCallback)>(window,
                                                                                      callback);
}
GLFWmousebuttonfun glfwSetMouseButtonCallback(GLFWwindow* window, GLFWmousebuttonfun callback) {
    return call_glfw<"glfwSetMouseButtonCallback", decltype(&glfwSetMouseButtonCallback)>(window,
                                                                                          callback);
}
GLFWscrollfun glfwSetScrollCallback(GLFWwindow* window, GLFWscrollfun callback) {
    return call_glfw<"glfwSetScrollCallback", decltype(&glfwSetScrollCallback)>(window, callback);
}

// ImGui's GLFW backend's (imgui_impl_glfw.cpp, in Debian's libimgui.a), beyond those above.
GLFWcharfun glfwSetCharCallback(GLFWwindow* window, GLFWcharfun callback) {
    return call_glfw<"glfwSetCharCallback", decltype(&glfwSetCharCallback)>(window, callback);
}
GLFWcursorenterfun glfwSetCursorEnterCallback(GLFWwindow* window, GLFWcursorenterfun callback) {
    return call_glfw<"glfwSetCursorEnterCallback", decltype(&glfwSetCursorEnterCallback)>(window,
                                                                                          callback);
}
GLFWwindowfocusfun glfwSetWindowFocusCallback(GLFWwindow* window, GLFWwindowfocusfun callback) {
    return call_glfw<"glfwSetWindowFocusCallback", decltype(&glfwSetWindowFocusCallback)>(window,
                                                                                          callback);
}
GLFWmonitorfun glfwSetMonitorCallback(GLFWmonitorfun callback) {
    return call_glfw<"glfwSetMonitorCallback", decltype(&glfwSetMonitorCallback)>(callback);
}
GLFWcursor* glfwCreateStandardCursor(int shape) {
    return call_glfw<"glfwCreateStandardCursor", decltype(&glfwCreateStandardCursor)>(shape);
}
void glfwDestroyCursor(GLFWcursor* cursor) {
    call_glfw<"glfwDestroyCursor", decltype(&glfwDestroyCursor)>(cursor);
}
void glfwSetCursor(GLFWwindow* window, GLFWcursor* cursor) {
    call_glfw<"glfwSetCursor", decltype(&glfwSetCursor)>(window, cursor);
}
void glfwSetCursorPos(GLFWwindow* window, double x, double y) {
    call_glfw<"glfwSetCursorPos", decltype(&glfwSetCursorPos)>(window, x, y);
}
int glfwGetMouseButton(GLFWwindow* window, int button) {
    return call_glfw<"glfwGetMouseButton", decltype(&glfwGetMouseButton)>(window, button);
}
int glfwGetInputMode(GLFWwindow* window, int mode) {
    return call_glfw<"glfwGetInputMode", decltype(&glfwGetInputMode)>(window, mode);
}
void glfwSetInputMode(GLFWwindow* window, int mode, int value) {
    call_glfw<"glfwSetInputMode", decltype(&glfwSetInputMode)>(window, mode, value);
}
int glfwGetWindowAttrib(GLFWwindow* window, int attribute) {
    return call_glfw<"glfwGetWindowAttrib", decltype(&glfwGetWindowAttrib)>(window, attribute);
}
const char* glfwGetClipboardString(GLFWwindow* window) {
    return call_glfw<"glfwGetClipboardString", decltype(&glfwGetClipboardString)>(window);
}
void glfwSetClipboardString(GLFWwindow* window, const char* text) {
    call_glfw<"glfwSetClipboardString", decltype(&glfwSetClipboardString)>(window, text);
}
double glfwGetTime() {
    return call_glfw<"glfwGetTime", decltype(&glfwGetTime)>();
}
const float* glfwGetJoystickAxes(int joystick, int* count) {
    return call_glfw<"glfwGetJoystickAxes", decltype(&glfwGetJoystickAxes)>(joystick, count);
}
const unsigned char* glfwGetJoystickButtons(int joystick, int* count) {
    return call_glfw<"glfwGetJoystickButtons", decltype(&glfwGetJoystickButtons)>(joystick, count);
}
