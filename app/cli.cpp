#include "app/commands.h"

#include <algorithm>
#include <string>
#include <vector>

namespace glint {

Cli::Cli() {
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string(GLINT_VERSION));
    commands = {add_render_command(app),  add_explain_command(app),  add_preview_command(app),
                add_compare_command(app), add_tradeoff_command(app), add_bench_command(app),
                add_info_command(app)};
}

namespace {

// How many single-character edits turn `a` into `b` (Levenshtein).
std::size_t edits(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

} // namespace

void Cli::parse(int argc, const char* const* argv) {
    if (argc > 1 && argv[1][0] != '-') {
        const std::string word = argv[1];
        std::string names, nearest;
        std::size_t best = 3; // at most two edits away counts as a typo
        bool known = false;
        for (const Command& command : commands) {
            const std::string& name = command.cli->get_name();
            known = known || name == word;
            names += (names.empty() ? "" : ", ") + name;
            if (const std::size_t d = edits(word, name); d < best) best = d, nearest = name;
        }
        if (!known)
            throw CLI::ParseError("no command '" + word + "'" +
                                      (nearest.empty() ? "" : "; did you mean '" + nearest + "'?") +
                                      " (glint's commands: " + names + ")",
                                  CLI::ExitCodes::ExtrasError);
    }
    app.parse(argc, argv);
}

const Command& Cli::chosen() const {
    for (const Command& command : commands)
        if (command.cli->parsed()) return command;
    throw std::logic_error("no subcommand parsed"); // require_subcommand(1) prevents it
}

} // namespace glint
