// `glint info`: what this build is and what it can use.
#include "app/commands.h"

#include "raster/gl_context.h"
#include "trace/kernel.h"

#include <tbb/task_arena.h>
#include <tbb/version.h>

#include <cstdio>
#include <string>

namespace glint {

Command add_info_command(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Show version, build and threading facts");
    return {cmd, [] {},
            [] {
                std::printf("glint %s (%s build)\n", GLINT_VERSION, GLINT_BUILD_TYPE);
                std::printf("threads: %d (oneTBB %d.%d)\n", tbb::this_task_arena::max_concurrency(),
                            TBB_VERSION_MAJOR, TBB_VERSION_MINOR);
                std::string kernels;
                for (const Kernel k : available_kernels())
                    kernels += (kernels.empty() ? "" : ", ") + std::string(name_of(k));
                std::printf("kernel: %s (BVH box tests; this processor has %s; GLINT_KERNEL "
                            "chooses)\n",
                            std::string(name_of(active_kernel())).c_str(), kernels.c_str());
                for (const GlBackend backend : {GlBackend::osmesa, GlBackend::egl}) {
                    try {
                        const auto context = make_context(backend);
                        std::printf("OpenGL (%s): %s, %s\n", std::string(name_of(backend)).c_str(),
                                    context->renderer().c_str(), context->version().c_str());
                    } catch (const GlError& e) {
                        std::printf("OpenGL (%s): unavailable: %s\n",
                                    std::string(name_of(backend)).c_str(), e.what());
                    }
                }
                const std::vector<EglDevice> devices = egl_devices();
                std::printf("EGL devices: %zu%s\n", devices.size(),
                            devices.empty() ? " (none enumerated)" : "");
                for (std::size_t i = 0; i < devices.size(); ++i)
                    std::printf("  %zu: %s%s\n", i, devices[i].name.c_str(),
                                devices[i].software ? " (software: Mesa llvmpipe)"
                                                    : " (hardware: --gl egl draws here)");
                return 0;
            }};
}

} // namespace glint
