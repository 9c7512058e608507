// The glint subcommands, each registered on the CLI11 app and run after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint {

struct Command {
    CLI::App* cli;            // the subcommand, to ask whether it was chosen
    std::function<int()> run; // runs it after parsing; returns the exit code
};

Command add_render_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_info_command(CLI::App& app);

} // namespace glint
