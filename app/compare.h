// `glint compare`'s parts: hybrid against ray mode (compare_command.cpp, as it always was) and
// any two settings against each other with each differing pixel's cause (compare_sides.cpp,
// docs/DIFFERENCES.md); `glint explain --against` reads a side's flags the
// same way.
#pragma once

#include "app/options.h"
#include "frame/difference.h"

#include <atomic>
#include <cstdio>
#include <memory>
#include <string>

namespace glint {

struct CompareArgs {
    SceneOptions scene;
    FrameOptions frame;
    std::string prefix; // -o
    std::string json;
    std::string a, b; // --a, --b: each side's flags
    CLI::Option* a_option = nullptr;
    CLI::Option* b_option = nullptr;
    bool exr = false; // --exr: also the float error as PREFIX-heat.exr

    bool sides() const { return a_option->count() > 0 || b_option->count() > 0; }
    // compare's options (the command's and the Python module's Scene.compare).
    void add_to(CLI::App& cmd);
};

// One side of a comparison from its flags (`flag`: "--a", "--b", "--against", named in every
// message): the render flags a side may set, or `exact` (what `glint tradeoff` compares
// against: ray traced in double precision, depth kMaxDepth, no cut-off), optionally followed by
// flags that change it. What is not given is the command's own (`shared`, `frame`; `base`: the
// scene loaded with the command's overrides). UsageError on an empty string, an unknown flag, a
// bad value or a flag both sides must share (--size, --camera, --gl).
Side parse_side(const std::string& flag, const std::string& text, const Scene& base,
                const SceneOptions& shared, const FrameOptions& frame);

// Two settings rendered and compared, pixel by pixel: what `glint compare --a … --b …` prints and
// writes, and what the Python module's Scene.compare returns.
struct ComparedSides {
    std::unique_ptr<const RenderedSide> a, b;
    FrameDifference difference; // per pixel: the error and its cause
    ImageDifference image;      // PSNR, RMSE, the largest error
    std::string json;           // as --json writes it (docs/DIFFERENCES.md)
};

// The two-sided compare: checks (nothing rendered or written), the comparison (Cancelled once
// `cancel` is set: between the sides, or between tiles of either; a line on `progress`, where
// given, as each side starts) and the whole run.
void check_compare_sides(const CompareArgs& args);
ComparedSides compare_sides(const CompareArgs& args, const std::atomic<bool>* cancel = nullptr,
                            std::FILE* progress = nullptr);
int run_compare_sides(const CompareArgs& args);

} // namespace glint
