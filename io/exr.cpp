#include "io/exr.h"

#include <dlfcn.h>

#include <stdexcept>

namespace glint {

namespace {

// glint_encode_exr in the EXR plug-in (io/exr_plugin.cpp), opened on first use; null where it
// cannot be, with dlopen's reason in `problem`.
using Encoder = bool (*)(const ExrLayers*, std::string*, std::string*) noexcept;
using Decoder = bool (*)(const char*, int*, int*, std::vector<float>*, std::string*) noexcept;
struct Plugin {
    Encoder encode = nullptr;
    Decoder decode = nullptr;
    std::string problem;
};

const Plugin& plugin() {
    static const Plugin opened = [] {
        Plugin p;
        if (void* handle = ::dlopen(GLINT_EXR_PLUGIN, RTLD_NOW | RTLD_LOCAL)) {
            p.encode = reinterpret_cast<Encoder>(::dlsym(handle, "glint_encode_exr"));
            p.decode = reinterpret_cast<Decoder>(::dlsym(handle, "glint_decode_exr"));
        }
        if (!p.encode || !p.decode) {
            const char* reason = ::dlerror();
            p.problem = reason ? reason : "no glint_encode_exr or glint_decode_exr in it";
        }
        return p;
    }();
    return opened;
}

} // namespace

std::string encode_exr(const ExrLayers& layers) {
    const Plugin& exr = plugin();
    if (!exr.encode)
        throw std::runtime_error("EXR: cannot open the OpenEXR plug-in built with glint: " +
                                 exr.problem);
    std::string bytes, error;
    if (!exr.encode(&layers, &bytes, &error)) throw std::runtime_error(error);
    return bytes;
}

void write_exr(const std::filesystem::path& path, const ExrLayers& layers) {
    write_encoded(path, "OpenEXR", [&] { return encode_exr(layers); });
}

ExrRgb read_exr_rgb(const std::filesystem::path& path) {
    const Plugin& exr = plugin();
    if (!exr.decode)
        throw std::runtime_error("cannot open the OpenEXR plug-in built with glint: " +
                                 exr.problem);
    ExrRgb out;
    std::string error;
    if (!exr.decode(path.c_str(), &out.width, &out.height, &out.rgb, &error))
        throw std::runtime_error(error);
    return out;
}

} // namespace glint
