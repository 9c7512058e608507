// GLFW, opened on first use rather than linked (preview/glfw_library.cpp defines the GLFW
// functions glint and ImGui's GLFW backend call, each forwarding to the library's own).
#pragma once

#include "raster/gl_context.h"

namespace glint {

// The library opened: GLFW 3's, as Debian's libglfw3 installs it.
inline constexpr const char* kGlfwLibrary = "libglfw.so.3";

// Opens GLFW where it is not open yet. Throws GlError where it cannot be used: "could not load
// GLFW (libglfw3): " and dlopen's reason, or "libglfw.so.3 lacks glfwInit".
void open_glfw();

} // namespace glint
