// glint: renders scenes by ray tracing (Ray Tracing III). Exit codes: 0 ok, 1 runtime failure,
// 2 usage or bad input.
#include "app/commands.h"
#include "app/distributed.h"
#include "trace/kernel.h"

#include <cstdlib>
#include <iostream>

namespace {

// Under mpirun: the command, or a refusal for the commands that do not run across ranks (every
// rank would do the whole work and write the same files).
int run_command(const glint::Cli& cli) {
    const glint::Command& command = cli.chosen();
    const std::string name = command.cli->get_name();
    if (glint::on_ranks() && name != "render" && name != "tradeoff") {
        if (glint::rank() == 0)
            std::cerr << "glint: error: only `glint render` and `glint tradeoff` run across MPI "
                         "ranks; run `glint "
                      << command.cli->get_name() << "` without mpirun\n";
        return 2;
    }
    return command.run();
}

// GLINT_KERNEL, when set, must name a kernel this processor has (trace/kernel.h).
bool kernel_choice_stands() {
    const char* requested = std::getenv("GLINT_KERNEL");
    if (!requested) return true;
    const glint::KernelChoice choice = glint::choose_kernel(requested);
    if (choice.problem.empty()) return true;
    if (glint::rank() == 0)
        std::cerr << "glint: error: GLINT_KERNEL=" << requested << " " << choice.problem << "\n";
    return false;
}

} // namespace

int main(int argc, char** argv) {
    if (const int code = glint::start_ranks(argv); code >= 0) return code;
    glint::Cli cli;
    int code = 0;
    try {
        cli.parse(argc, argv);
        code = kernel_choice_stands() ? run_command(cli) : 2;
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) {
            code = glint::rank() == 0 ? cli.app.exit(e) : 0; // --help, --version
        } else {
            if (glint::rank() == 0)
                std::cerr << "glint: error: " << e.what() << "\nRun 'glint --help' for usage.\n";
            code = 2;
        }
    }
    glint::finish_ranks();
    return code;
}
