#include "app/commands.h"

namespace glint {

Cli::Cli() {
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string(GLINT_VERSION));
    commands = {add_render_command(app),  add_explain_command(app),  add_preview_command(app),
                add_compare_command(app), add_tradeoff_command(app), add_bench_command(app),
                add_info_command(app)};
}

const Command& Cli::chosen() const {
    for (const Command& command : commands)
        if (command.cli->parsed()) return command;
    throw std::logic_error("no subcommand parsed"); // require_subcommand(1) prevents it
}

} // namespace glint
