// `glint bench`: runs the Google Benchmark suites (bench/), passing any further arguments on.
#include "app/commands.h"

#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <vector>

namespace glint {

Command add_bench_command(CLI::App& app) {
    auto arguments = std::make_shared<std::vector<std::string>>();
    CLI::App* cmd =
        app.add_subcommand("bench", "Run the benchmarks (Google Benchmark flags pass through)");
    cmd->allow_extras();
    // Its flags belong to Google Benchmark, which checks them itself.
    return {cmd, [] {},
            [cmd, arguments] {
                const std::string binary = GLINT_BENCH_BINARY;
                if (!std::filesystem::exists(binary)) {
                    std::fprintf(
                        stderr,
                        "glint: error: %s is not built (configure with -DGLINT_BUILD_BENCH=ON)\n",
                        binary.c_str());
                    return 1;
                }
                std::vector<std::string> args{binary};
                for (const std::string& extra : cmd->remaining()) args.push_back(extra);
                std::vector<char*> argv;
                for (std::string& a : args) argv.push_back(a.data());
                argv.push_back(nullptr);
                std::fflush(stdout);
                execv(binary.c_str(), argv.data());
                std::perror("glint: error: cannot run the benchmarks");
                return 1;
            }};
}

} // namespace glint
