// OSMesa: Mesa's off-screen GL (llvmpipe), in Debian 12; Mesa removed it in 25.1 (see EGL).
#include "raster/gl_context.h"

#include <glad/gl.h> // before GL/osmesa.h, which would otherwise pull in GL/gl.h

#include <GL/osmesa.h>

#include <array>

namespace glint {
namespace {

class OsmesaContext final : public GlContext {
  public:
    OsmesaContext() {
        const int attributes[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  0,
                                  OSMESA_STENCIL_BITS,
                                  0,
                                  OSMESA_ACCUM_BITS,
                                  0,
                                  OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  3,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  3,
                                  0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_) throw GlError("OSMesa could not create an OpenGL 3.3 core context");
        // OSMesa needs a live buffer to make a context current; glint renders into its own FBOs.
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
            OSMesaDestroyContext(context_);
            throw GlError("OSMesa could not make its context current");
        }
        try {
            load_functions(reinterpret_cast<void* (*)(const char*)>(OSMesaGetProcAddress));
        } catch (...) {
            OSMesaDestroyContext(context_);
            throw;
        }
    }
    ~OsmesaContext() override { OSMesaDestroyContext(context_); }

  private:
    OSMesaContext context_ = nullptr;
    std::array<unsigned char, 4> buffer_{};
};

} // namespace

std::unique_ptr<GlContext> make_osmesa_context() {
    return std::make_unique<OsmesaContext>();
}

} // namespace glint
