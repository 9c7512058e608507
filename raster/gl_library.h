// The GL libraries glint opens when a context is first made rather than links (OSMesa, EGL;
// and GLFW for the preview's window, preview/glfw_library.cpp): a process that draws nothing,
// a ray-mode render, loads none of them. For raster/ and preview/ alone.
#pragma once

#include "raster/gl_context.h"

#include <dlfcn.h>

#include <initializer_list>
#include <string>

namespace glint {

// The first of `names` that opens (kept open for the process, so that the leak checker still
// sees its allocations' module); else GlError "could not load WHAT: " with the first's reason.
void* open_gl_library(std::initializer_list<const char*> names, const std::string& what);

// Sets `function` to `library`'s `name`; else GlError "LIBRARY lacks NAME".
template <class Function>
void find_function(void* library, Function& function, const char* name,
                   const std::string& library_name) {
    function = reinterpret_cast<Function>(dlsym(library, name));
    if (!function) throw GlError(library_name + " lacks " + name);
}

} // namespace glint
