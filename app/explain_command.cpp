// `glint explain [SCENE] X Y`: one pixel's ray tree, in the lecture's notation or as JSON
// (frame/explain.h, docs/EXPLAIN.md).
#include "app/compare.h"
#include "app/explain.h"

#include "frame/explain.h"
#include "frame/explain_against.h"
#include "io/write_file.h"
#include "trace/image.h"

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace glint {
namespace {

struct ExplainJob {
    Scene scene;
    int x = 0, y = 0, a = 0, b = 0;
    bool sample_given = false;
    std::optional<Side> against;
};

int whole_number(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    int value = 0;
    try {
        value = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw UsageError(what + " '" + text + "' is not a whole number");
    return value;
}

// Whether a positional is a number ("12", "1.5", "-3") rather than a scene's path: given X Y
// alone, the scene's slot takes X, and X is then judged as a pixel's column.
bool looks_like_a_number(const std::string& text) {
    if (text.empty()) return false;
    char* end = nullptr;
    std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size();
}

// Every check on the input, before anything is traced or written.
ExplainJob prepare(ExplainArgs& args) {
    // Positionals fill in order: given X Y alone, the scene's slot took X.
    if (args.pixel.size() == 1 && looks_like_a_number(args.scene.scene)) {
        args.pixel.insert(args.pixel.begin(), args.scene.scene);
        args.scene.scene.clear();
    }
    if (args.pixel.size() != 2)
        throw UsageError("explain needs the pixel: glint explain [SCENE] X Y (column, row)");
    if (!args.json.empty()) check_output(args.json, "--json");
    args.frame.settings(); // refuses settings that contradict each other (--aa-sample-ids)
    ExplainJob job;
    job.x = whole_number(args.pixel[0], "X");
    job.y = whole_number(args.pixel[1], "Y");
    job.scene = args.scene.load();
    const Camera& camera = job.scene.camera;
    if (job.x < 0 || job.x >= camera.width || job.y < 0 || job.y >= camera.height)
        throw UsageError("pixel (" + args.pixel[0] + ", " + args.pixel[1] + ") is outside the " +
                         std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                         " image (X 0 to " + std::to_string(camera.width - 1) + ", Y 0 to " +
                         std::to_string(camera.height - 1) + ")");
    const int n = job.scene.render.samples;
    job.a = job.b = n / 2; // the centre sample (the pixel centre's ray for odd N)
    if (!args.sample.empty()) {
        const std::size_t comma = args.sample.find(',');
        if (comma == std::string::npos)
            throw UsageError("--sample " + args.sample +
                             ": expected A,B (column, row in the grid)");
        job.sample_given = true;
        job.a = whole_number(args.sample.substr(0, comma), "--sample A");
        job.b = whole_number(args.sample.substr(comma + 1), "--sample B");
        if (job.a < 0 || job.a >= n || job.b < 0 || job.b >= n)
            throw UsageError("--sample " + args.sample + " is outside the pixel's " +
                             std::to_string(n) + "x" + std::to_string(n) +
                             " grid of samples (A and B from 0 to " + std::to_string(n - 1) + ")");
    }
    if (args.against_option->count())
        job.against = parse_side("--against", args.against, job.scene, args.scene, args.frame);
    return job;
}

// --against: the pixel under explain's own settings (A) and the other side's (B).
Explained explain_both(const ExplainArgs& args, const ExplainJob& job) {
    Side own;
    own.label = "(explain's own settings)";
    own.scene = job.scene, own.accel = args.scene.accel_kind(), own.frame = args.frame.settings();
    const RenderedSide a(std::move(own));
    const RenderedSide b(*job.against);
    const int n = job.scene.render.samples;
    const PixelAgainst p =
        explain_against(a, b, job.x, job.y, job.sample_given ? job.b * n + job.a : -1);
    const std::string scene = args.scene.scene_path().string();
    return {against_text(a, b, p, scene), against_json(a, b, p, scene)};
}

int run_explain(ExplainArgs& args) {
    const Explained e = explain(args);
    std::fputs(e.text.c_str(), stdout);
    if (!args.json.empty()) {
        write_file_atomically(args.json, e.json);
        std::printf("glint: wrote %s\n", args.json.c_str());
    }
    return 0;
}

} // namespace

void ExplainArgs::add_to(CLI::App& cmd) {
    scene.add_to(cmd);
    cmd.add_option("pixel", pixel, "X Y: the pixel's column and row (0, 0: top left)")
        ->expected(1, 2);
    frame.add_to(cmd, true);
    cmd.add_option("--sample", sample,
                   "A,B: which sample of the pixel's NxN grid to explain; default the centre "
                   "one (N/2, N/2)");
    cmd.add_option("--json", json, "Also write the explanation as JSON (docs/EXPLAIN.md)");
    against_option = cmd.add_option(
        "--against", against,
        "Another setting's flags, quoted (\"--max-depth 2\"), or exact: the pixel's two ray trees "
        "side by side, where they part and why (docs/EXPLAIN.md)");
    // render's outputs: explain writes none of them.
    refuse_option(cmd, "-o,--output",
                  "explain writes no image: it prints the pixel's ray tree (--json writes it as "
                  "JSON); `glint render -o` writes the image");
    refuse_option(cmd, "--stats",
                  "render's: explain prints the pixel's rays itself (and --json writes them)");
    refuse_option(cmd, "--aov",
                  "render's (an EXR's channels): explain prints the pixel's primary hit itself");
    refuse_option(cmd, "--aa-map", "render's: explain says whether its pixel took the sample grid");
}

Explained explain(ExplainArgs& args) {
    const ExplainJob job = prepare(args);
    if (job.against) return explain_both(args, job);
    const World world(job.scene, args.scene.accel_kind());
    const PixelExplanation e =
        explain_frame_pixel(world, args.frame.settings(), job.x, job.y, job.a, job.b);
    const std::string settings = args.frame.describe();
    const std::string scene = args.scene.scene_path().string();
    std::string what = scene + " (" + std::to_string(job.scene.camera.width) + "x" +
                       std::to_string(job.scene.camera.height) + "), " + settings;
    if (const std::string aa = describe_antialiasing(job.scene.render); !aa.empty())
        what += ", " + aa;
    return {explanation_text(job.scene, world, e, what),
            explanation_json(job.scene, world, e, scene, settings)};
}

namespace {} // namespace

Command add_explain_command(CLI::App& app) {
    auto args = std::make_shared<ExplainArgs>();
    CLI::App* cmd = app.add_subcommand(
        "explain", "Explain one pixel: its ray tree with every term, as the render computes it");
    args->add_to(*cmd);
    return {cmd, [args] { prepare(*args); },
            [args] { return guarded([&] { return run_explain(*args); }); }};
}

} // namespace glint
