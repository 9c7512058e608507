// OSMesa: Mesa's off-screen GL (llvmpipe), in Debian 12; Mesa removed it in 25.1 (see EGL).
#include "raster/gl_context.h"

#include "raster/gl_library.h"

#include <glad/gl.h> // before GL/osmesa.h, which would otherwise pull in GL/gl.h

#include <GL/osmesa.h>

#include <array>
#include <string>

namespace glint {
namespace {

// libOSMesa is opened when the first context is made, not linked: it brings llvmpipe and LLVM
// with it, whose loading and relocation cost every glint process about 65 ms before main()
// (`glint --version` took 78 ms, 13 without it: docs/PERFORMANCE.md, "Start-up and the
// write"), though only the item buffer uses it. Once opened it stays open, so that the leak
// checker still sees its allocations' module (tools/lsan.supp; raster/gl_library.h).
struct OsmesaLibrary {
    decltype(&OSMesaCreateContextAttribs) create_context_attribs;
    decltype(&OSMesaMakeCurrent) make_current;
    decltype(&OSMesaDestroyContext) destroy_context;
    decltype(&OSMesaGetProcAddress) get_proc_address;
};

const OsmesaLibrary& osmesa() {
    static const OsmesaLibrary functions = [] {
        // The package libosmesa6, which ./glint installs.
        void* library = open_gl_library({"libOSMesa.so.8", "libOSMesa.so"}, "OSMesa (libosmesa6)");
        OsmesaLibrary f{};
        find_function(library, f.create_context_attribs, "OSMesaCreateContextAttribs", "libOSMesa");
        find_function(library, f.make_current, "OSMesaMakeCurrent", "libOSMesa");
        find_function(library, f.destroy_context, "OSMesaDestroyContext", "libOSMesa");
        find_function(library, f.get_proc_address, "OSMesaGetProcAddress", "libOSMesa");
        return f;
    }();
    return functions;
}

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
        context_ = library_.create_context_attribs(attributes, nullptr);
        if (!context_) throw GlError("OSMesa could not create an OpenGL 3.3 core context");
        // OSMesa needs a live buffer to make a context current; glint renders into its own FBOs.
        if (!library_.make_current(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
            library_.destroy_context(context_);
            throw GlError("OSMesa could not make its context current");
        }
        try {
            load_functions(reinterpret_cast<void* (*)(const char*)>(library_.get_proc_address));
        } catch (...) {
            library_.destroy_context(context_);
            throw;
        }
    }
    ~OsmesaContext() override { library_.destroy_context(context_); }

  private:
    const OsmesaLibrary& library_ = osmesa();
    OSMesaContext context_ = nullptr;
    std::array<unsigned char, 4> buffer_{};
};

} // namespace

std::unique_ptr<GlContext> make_osmesa_context() {
    return std::make_unique<OsmesaContext>();
}

} // namespace glint
