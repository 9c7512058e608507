// glint: renders scenes by ray tracing (Ray Tracing III). Exit codes: 0 ok, 1 runtime failure,
// 2 usage or bad input.
#include "app/commands.h"

#include <iostream>

int main(int argc, char** argv) {
    glint::Cli cli;
    try {
        cli.app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return cli.app.exit(e); // --help, --version
        std::cerr << "glint: error: " << e.what() << "\nRun 'glint --help' for usage.\n";
        return 2;
    }
    return cli.chosen().run();
}
