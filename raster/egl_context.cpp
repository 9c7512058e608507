// EGL with no display: on the first hardware device EGL enumerates (EGL_EXT_platform_device: a
// GPU's driver), else on Mesa's surfaceless platform (EGL_MESA_platform_surfaceless: llvmpipe,
// as here), and the way glint keeps working once OSMesa is gone (Mesa 25.1+).
#include "raster/gl_context.h"

#include "raster/gl_library.h"

#include <glad/gl.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#ifdef GLINT_SANITIZE
#include <link.h>

#include <string_view>
#endif

namespace glint {
namespace {

#ifdef GLINT_SANITIZE
// LeakSanitizer checks at exit, after eglTerminate has unloaded Mesa's DRI driver (dlclose of
// swrast_dri.so). Two blocks the driver still points to from its own globals (2 × 56 bytes,
// allocated inside it) then look leaked, from frames in a module that no longer exists, so no
// suppression can name them. Keeping the driver loaded keeps them reachable; the leak check
// stays on for everything else. Sanitizer builds only.
void keep_dri_drivers_loaded() {
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void*) {
            const std::string_view name = info->dlpi_name;
            if (name.ends_with("_dri.so"))
                dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
}
#endif

// libEGL (glvnd's dispatcher, with libGLdispatch) is opened when EGL is first asked for, not
// linked, as OSMesa is: only the hybrid pass with --gl egl and `glint info` use it, and loading
// it cost every process about 2 ms (`glint --version` 13.9 → 12.0 ms: docs/PERFORMANCE.md,
// "EGL opened only to draw").
struct EglLibrary {
    decltype(&eglGetProcAddress) get_proc_address;
    decltype(&eglInitialize) initialize;
    decltype(&eglTerminate) terminate;
    decltype(&eglBindAPI) bind_api;
    decltype(&eglCreateContext) create_context;
    decltype(&eglMakeCurrent) make_current;
    decltype(&eglDestroyContext) destroy_context;
};

const EglLibrary& egl() {
    static const EglLibrary functions = [] {
        void* library = open_gl_library({"libEGL.so.1", "libEGL.so"}, "EGL (libegl1)");
        EglLibrary f{};
        find_function(library, f.get_proc_address, "eglGetProcAddress", "libEGL");
        find_function(library, f.initialize, "eglInitialize", "libEGL");
        find_function(library, f.terminate, "eglTerminate", "libEGL");
        find_function(library, f.bind_api, "eglBindAPI", "libEGL");
        find_function(library, f.create_context, "eglCreateContext", "libEGL");
        find_function(library, f.make_current, "eglMakeCurrent", "libEGL");
        find_function(library, f.destroy_context, "eglDestroyContext", "libEGL");
        return f;
    }();
    return functions;
}

template <class Function> Function egl_function(const char* name) {
    return reinterpret_cast<Function>(egl().get_proc_address(name));
}

struct Device {
    EGLDeviceEXT handle;
    EglDevice facts;
};

std::vector<Device> enumerate_devices() {
    const auto query_devices = egl_function<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    const auto query_string =
        egl_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
    EGLint count = 0;
    if (!query_devices || !query_string || !query_devices(0, nullptr, &count) || count <= 0)
        return {};
    std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
    if (!query_devices(count, handles.data(), &count)) return {};
    handles.resize(static_cast<std::size_t>(count));
    std::vector<Device> devices;
    for (EGLDeviceEXT handle : handles) {
        Device d{handle, {}};
        const char* extensions = query_string(handle, EGL_EXTENSIONS);
        d.facts.extensions = extensions ? extensions : "";
        d.facts.software = d.facts.extensions.find("EGL_MESA_device_software") != std::string::npos;
        if (d.facts.extensions.find("EGL_EXT_device_drm") != std::string::npos)
            if (const char* file = query_string(handle, EGL_DRM_DEVICE_FILE_EXT))
                d.facts.name = file;
        if (d.facts.name.empty()) d.facts.name = "no DRM device file";
        devices.push_back(std::move(d));
    }
    return devices;
}

class EglContext final : public GlContext {
  public:
    // On `device` (EGL_PLATFORM_DEVICE_EXT), or without one on Mesa's surfaceless platform.
    explicit EglContext(EGLDeviceEXT device) {
        const auto get_platform_display =
            egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
        if (!get_platform_display) throw GlError("EGL lacks eglGetPlatformDisplayEXT");
        display_ = device ? get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr)
                          : get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                                 nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !egl().initialize(display_, &major, &minor))
            throw GlError(device ? "EGL could not open a display on the device"
                                 : "EGL could not open a surfaceless display (Mesa's "
                                   "EGL_MESA_platform_surfaceless)");
#ifdef GLINT_SANITIZE
        keep_dri_drivers_loaded();
#endif
        // Desktop GL finds no EGLConfig here, so the context is made without one
        // (EGL_KHR_no_config_context) and renders only into framebuffer objects.
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     3,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
        if (!egl().bind_api(EGL_OPENGL_API) ||
            (context_ = egl().create_context(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                             attributes)) == EGL_NO_CONTEXT ||
            !egl().make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            release();
            throw GlError("EGL could not create an OpenGL 3.3 core context");
        }
        try {
            load_functions(reinterpret_cast<void* (*)(const char*)>(egl().get_proc_address));
        } catch (...) {
            release();
            throw;
        }
    }
    ~EglContext() override {
        release();
    }

  private:
    void release() {
        if (context_ != EGL_NO_CONTEXT) {
            egl().make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            egl().destroy_context(display_, context_);
        }
        egl().terminate(display_);
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace

std::unique_ptr<GlContext> make_egl_context() {
    for (const Device& device : enumerate_devices()) {
        if (device.facts.software) continue;
        try {
            return std::make_unique<EglContext>(device.handle);
        } catch (const GlError&) {
            // A device that cannot make a 3.3 core context: the next, or surfaceless below.
        }
    }
    return std::make_unique<EglContext>(nullptr);
}

std::vector<EglDevice> egl_devices() {
    std::vector<EglDevice> facts;
    try {
        for (Device& device : enumerate_devices()) facts.push_back(std::move(device.facts));
    } catch (const GlError&) {
        // No libEGL to ask: no device it can enumerate.
    }
    return facts;
}

} // namespace glint
