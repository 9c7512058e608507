// A current OpenGL (3.3 core or later) context with no window, behind one small interface so
// that the item-buffer code does not care whether OSMesa, EGL or (later) GLFW made it.
#pragma once

#include "trace/names.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

enum class GlBackend { osmesa, egl };

template <> struct EnumNames<GlBackend> {
    static constexpr auto names = name_table("osmesa", "egl");
};

// No usable GL context: the message says what failed.
class GlError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class GlContext {
  public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    const std::string& renderer() const {
        return renderer_;
    } // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const { return version_; } // e.g. "4.5 (Core Profile) Mesa 22.3.6"

  protected:
    GlContext() = default;
    // Loads GL functions through `get_proc` (glad) for the context just made current, and checks
    // that it offers what the item buffer needs (3.3 core, clip control for reverse-Z).
    void load_functions(void* (*get_proc)(const char*));

  private:
    std::string renderer_, version_;
};

// Creates and makes current a context of the given kind. Throws GlError. EGL takes the first
// hardware device it enumerates (EGL_EXT_platform_device), and otherwise, or when that device
// cannot make a context, Mesa's surfaceless platform (llvmpipe).
std::unique_ptr<GlContext> make_context(GlBackend backend);

// The devices EGL enumerates (EGL_EXT_device_enumeration), in its order; empty where EGL cannot.
struct EglDevice {
    std::string name;      // its DRM device file where EGL_EXT_device_drm names one
    bool software = false; // EGL_MESA_device_software: Mesa's llvmpipe, not a GPU
    std::string extensions;
};
std::vector<EglDevice> egl_devices();

} // namespace glint
