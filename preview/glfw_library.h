// GLFW, opened on first use rather than linked (preview/glfw_library.cpp defines the GLFW
// functions glint and ImGui's GLFW backend call, each forwarding to the library's own).
#pragma once

#include <string>

namespace glint {

// The library opened: GLFW 3's, as Debian's libglfw3 installs it.
inline constexpr const char* kGlfwLibrary = "libglfw.so.3";

// Why GLFW cannot be used (dlopen's reason, or the library lacking glfwInit); empty where it can.
std::string glfw_library_problem();

} // namespace glint
