// libFuzzer target: any bytes as a glint command line, one argument per line. Parsing and every
// check a command makes before it works (flags, scene, output paths, memory) must end in
// success or one of glint's bad-input errors with a message: any other exception, a crash or a
// hang is a finding. Nothing is rendered or written.
#include "app/commands.h"
#include "app/options.h"
#include "io/error.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {
std::string scratch; // removed at exit
}

// Runs in a scratch directory holding a link to the shipped scenes, so that seeds can name
// scenes/default.json and the default output directory (out/) lands there; stdin is empty.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    scratch = (fs::temp_directory_path() / "glint-cli-fuzz-XXXXXX").string();
    if (!mkdtemp(scratch.data()) || chdir(scratch.c_str()) != 0) std::abort();
    std::atexit([] {
        std::error_code ec;
        fs::remove_all(scratch, ec);
    });
    fs::create_directory_symlink(fs::path(GLINT_SOURCE_DIR) / "scenes", "scenes");
    if (!std::freopen("/dev/null", "r", stdin)) std::abort();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args{"glint"};
    std::string arg;
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == '\n') {
            args.push_back(arg);
            arg.clear();
        } else {
            arg += static_cast<char>(data[i]);
        }
    }
    if (!arg.empty()) args.push_back(arg);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());

    glint::Cli cli;
    try {
        cli.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError&) {
        return 0; // CLI11's own message, exit 2 (or 0 for --help, --version)
    }
    try {
        cli.chosen().check();
    } catch (const glint::UsageError& e) {
        if (!*e.what()) std::abort();
    } catch (const glint::SceneError& e) {
        if (!*e.what()) std::abort();
    }
    return 0;
}
