#include "raster/gl_context.h"

#include "raster/gl_library.h"

#include <glad/gl.h>

namespace glint {

std::unique_ptr<GlContext> make_osmesa_context();
std::unique_ptr<GlContext> make_egl_context();

void GlContext::load_functions(void* (*get_proc)(const char*)) {
    // One glad table serves whichever context is current: reload whenever one is made current.
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(get_proc));
    if (version == 0) throw GlError("could not load OpenGL functions");
    if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33)
        throw GlError("OpenGL 3.3 core is needed, the context offers " +
                      std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                      std::to_string(GLAD_VERSION_MINOR(version)));
    if (!GLAD_GL_ARB_clip_control)
        throw GlError("the GL context lacks ARB_clip_control (needed for reverse-Z depth)");
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

void* open_gl_library(std::initializer_list<const char*> names, const std::string& what) {
    std::string why;
    for (const char* name : names) {
        if (void* library = dlopen(name, RTLD_NOW | RTLD_LOCAL)) return library;
        if (why.empty()) why = dlerror();
    }
    throw GlError("could not load " + what + ": " + why);
}

std::unique_ptr<GlContext> make_context(GlBackend backend) {
    return backend == GlBackend::osmesa ? make_osmesa_context() : make_egl_context();
}

} // namespace glint
