// The glint subcommands, each registered on the CLI11 app and run after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint {

struct Command {
    CLI::App* cli; // the subcommand, to ask whether it was chosen
    // Validates everything the command was given (flags, scene, output paths, memory), without
    // rendering or writing output; throws UsageError or SceneError. `run` does it first too.
    std::function<void()> check;
    std::function<int()> run; // runs it after parsing; returns the exit code
};

Command add_render_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_tradeoff_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_info_command(CLI::App& app);
Command add_preview_command(CLI::App& app);
Command add_explain_command(CLI::App& app);

// The whole command line: `glint` and its subcommands. main() and the command-line fuzzer
// (fuzz/cli_fuzzer.cpp) build it the same way.
struct Cli {
    CLI::App app{"glint: a hybrid item-buffer / ray-tracing renderer (Ray Tracing III)"};
    std::vector<Command> commands;

    Cli();
    // app.parse, after refusing a first word that is no command (a typo: `glint rendr`) with the
    // nearest command's name; throws CLI::ParseError (exit code 2) as app.parse does.
    void parse(int argc, const char* const* argv);
    // The chosen subcommand after a successful parse().
    const Command& chosen() const;
};

} // namespace glint
