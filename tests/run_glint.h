// Running the glint command as a user does, from a test: a fresh directory per test (so tests
// can run in parallel under ctest), the command run there, its exit code and what it printed.
// The including target defines GLINT_BINARY, the path of the glint executable.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace glint::testing {

struct Outcome {
    int exit_code;
    std::string out, err;
};

inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// An empty directory named after the running test, under GROUP in the test temporary directory.
inline std::filesystem::path fresh_dir(const std::string& group) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / group /
                                (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// Runs `glint ARGS` in DIR, with ENVIRONMENT (assignments) before it and no input.
inline Outcome glint(const std::filesystem::path& dir, const std::string& args,
                     const std::string& environment = "") {
    const std::string command = "cd '" + dir.string() + "' && " + environment + " '" GLINT_BINARY "' " +
                                args + " >stdout.txt 2>stderr.txt </dev/null";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout.txt"),
            slurp(dir / "stderr.txt")};
}

} // namespace glint::testing
