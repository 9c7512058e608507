// `glint info`: what this build is and what it can use.
#include "app/commands.h"

#include <tbb/task_arena.h>
#include <tbb/version.h>

#include <cstdio>

namespace glint {

Command add_info_command(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Show version, build and threading facts");
    return {cmd, [] {
                std::printf("glint %s (%s build)\n", GLINT_VERSION, GLINT_BUILD_TYPE);
                std::printf("threads: %d (oneTBB %d.%d)\n", tbb::this_task_arena::max_concurrency(),
                            TBB_VERSION_MAJOR, TBB_VERSION_MINOR);
                std::printf("OpenGL: not built yet (the item buffer is a separate issue)\n");
                return 0;
            }};
}

} // namespace glint
