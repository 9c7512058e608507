// `glint bench`: runs the Google Benchmark suites (bench/), passing any further arguments on.
#include "app/commands.h"
#include "app/options.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace glint {

namespace {

constexpr std::string_view kOutFlag = "--benchmark_out=";

// Runs the benchmark program and waits for it; returns its exit code (1 if it cannot run).
int run_and_wait(std::vector<std::string> args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    const pid_t child = fork();
    if (child == 0) {
        execv(argv[0], argv.data());
        std::perror("glint: error: cannot run the benchmarks");
        _exit(1);
    }
    int status = 0;
    if (child < 0 || waitpid(child, &status, 0) < 0) return 1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

} // namespace

Command add_bench_command(CLI::App& app) {
    CLI::App* cmd =
        app.add_subcommand("bench", "Run the benchmarks (Google Benchmark flags pass through)");
    cmd->allow_extras();
    const auto output = [cmd]() -> std::string {
        for (const std::string& extra : cmd->remaining())
            if (extra.starts_with(kOutFlag)) return extra.substr(kOutFlag.size());
        return {};
    };
    // The other flags belong to Google Benchmark, which checks them itself.
    const auto check = [output] {
        if (const std::string out = output(); !out.empty()) check_output(out, "--benchmark_out");
    };
    return {cmd, check, [cmd, check, output] {
                return guarded([&] {
                    check();
                    const std::string binary = GLINT_BENCH_BINARY;
                    if (!std::filesystem::exists(binary))
                        throw std::runtime_error(
                            binary + " is not built (configure with -DGLINT_BUILD_BENCH=ON)");
                    // --benchmark_out is written to a temporary file in the same directory and
                    // renamed when the run succeeds, like every output of glint.
                    const std::string out = output();
                    const std::string temp = out.empty() ? "" : out + ".partial";
                    std::vector<std::string> args{binary};
                    for (const std::string& extra : cmd->remaining())
                        args.push_back(extra.starts_with(kOutFlag) ? std::string(kOutFlag) + temp
                                                                   : extra);
                    const int status = run_and_wait(std::move(args));
                    if (!out.empty()) {
                        // Google Benchmark writes nothing when it rejects its own flags.
                        if (status == 0 && std::filesystem::exists(temp) &&
                            std::rename(temp.c_str(), out.c_str()) != 0)
                            throw std::runtime_error("cannot write " + out + ": " +
                                                     std::strerror(errno));
                        std::remove(temp.c_str());
                    }
                    return status;
                });
            }};
}

} // namespace glint
