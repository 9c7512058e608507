// `glint explain`'s settings and its one result, shared by the command and the Python module's
// Scene.explain (python/): the same options, checks and JSON.
#pragma once

#include "app/options.h"

#include <string>
#include <vector>

namespace glint {

struct ExplainArgs {
    SceneOptions scene;
    FrameOptions frame;
    std::vector<std::string> pixel; // X Y (prepare sorts out [SCENE] X Y)
    std::string sample;
    std::string json;
    std::string against; // --against: the other side's flags
    CLI::Option* against_option = nullptr;

    // explain's options, positionals and refusals.
    void add_to(CLI::App& cmd);
};

struct Explained {
    std::string text; // for people, as `glint explain` prints it
    std::string json; // as --json writes it (docs/EXPLAIN.md)
};

// Checks the arguments (UsageError, SceneError) and explains the pixel, or with --against the
// pixel under both settings.
Explained explain(ExplainArgs& args);

} // namespace glint
