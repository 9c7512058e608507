// glint: renders scenes by ray tracing (Ray Tracing III). Exit codes: 0 ok, 1 runtime failure,
// 2 usage or bad input.
#include "app/commands.h"

#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"glint: a hybrid item-buffer / ray-tracing renderer (Ray Tracing III)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string(GLINT_VERSION));
    const glint::Command commands[] = {glint::add_render_command(app),
                                       glint::add_compare_command(app),
                                       glint::add_bench_command(app), glint::add_info_command(app)};
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e); // --help, --version
        std::cerr << "glint: error: " << e.what() << "\nRun 'glint --help' for usage.\n";
        return 2;
    }
    for (const glint::Command& command : commands)
        if (command.cli->parsed()) return command.run();
    return 2; // unreachable: require_subcommand(1)
}
