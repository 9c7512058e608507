// `glint render`: load, prepare, draw the item buffer (hybrid), trace, write.
#include "app/options.h"
#include "app/progress.h"

#include "trace/cutoff.h"
#include "trace/image.h"
#include "trace/stopwatch.h"

#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include <cstdio>
#include <memory>

namespace glint {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
    SceneOptions scene;
    FrameOptions frame;
    std::string output;
    std::string stats;
};

// What a render needs once its input has been checked.
struct RenderJob {
    fs::path scene_path;
    fs::path output;
    Scene scene;
};

// Every check on the input, before anything is rendered or written.
RenderJob prepare(const RenderArgs& args) {
    RenderJob job{args.scene.scene_path(), args.output, {}};
    if (job.output.empty()) job.output = fs::path("out") / job.scene_path.stem().concat(".png");
    if (job.output.extension() != ".png")
        throw UsageError("-o " + job.output.string() + ": glint writes PNG files (.png)");
    if (args.output.empty()) create_output_directory(job.output);
    check_output(job.output, "-o");
    if (!args.stats.empty()) check_output(args.stats, "--stats");
    job.scene = args.scene.load();
    check_frame_memory(job.scene.camera, args.frame.settings().mode, 1);
    return job;
}

int run_render(const RenderArgs& args) {
    const Stopwatch total;
    Stopwatch phase;
    const RenderJob job = prepare(args);
    const Scene& scene = job.scene;
    const fs::path& scene_path = job.scene_path;
    const fs::path& output = job.output;
    const double load_seconds = phase.lap();
    World world(scene, args.scene.accel_kind());
    if (!args.stats.empty()) world.count_traversals(true);
    const double prepare_seconds = phase.lap();

    std::atomic<int> tiles_done{0};
    const FrameSettings settings = args.frame.settings();
    Frame frame;
    {
        // Primary hits and shading each visit every tile once.
        const Progress progress(
            "rendering", 2 * tile_count(scene.camera.width, scene.camera.height), tiles_done);
        frame = render_frame(world, settings, &tiles_done);
    }
    phase.restart();
    write_png(output, frame.result.image);
    const double write_seconds = phase.seconds();
    const double total_seconds = total.seconds();
    const int threads =
        args.frame.threads > 0 ? args.frame.threads : tbb::this_task_arena::max_concurrency();
    const RayCounts& rays = frame.result.rays;
    const PhaseTimes& t = frame.times;
    const CutoffBound cutoff = cutoff_bound(scene, frame.result);

    if (!args.stats.empty()) {
        nlohmann::ordered_json stats = {
            {"scene", scene_path.string()},
            {"output", output.string()},
            {"width", scene.camera.width},
            {"height", scene.camera.height},
            {"mode", args.frame.mode},
            {"threads", threads},
            {"max_depth", scene.render.max_depth},
            {"min_reflectivity", scene.render.min_reflectivity},
            {"seconds",
             {{"load", load_seconds},
              {"prepare", prepare_seconds},
              {"context", t.context},
              {"compile", t.compile},
              {"upload", t.upload},
              {"raster", t.raster},
              {"primary", t.primary},
              {"shading", t.shading},
              {"write", write_seconds},
              {"total", total_seconds}}},
            {"rays",
             {{"primary", rays.primary}, {"shadow", rays.shadow}, {"reflection", rays.reflection}}},
            {"cutoff",
             {{"bound_max_255", cutoff.max},
              {"pixels_over_1_255", cutoff.pixels_over_one},
              {"largest_omitted_weight", cutoff.largest_omitted_weight}}},
        };
        // Per ray: over every query the tracer made (primary, shadow and reflection rays, and in
        // hybrid mode the resolve's exact-interval queries, counted with the primary rays).
        const TraversalCounters counts = world.traversal_counts();
        const double queries = static_cast<double>(rays.primary + rays.shadow + rays.reflection);
        stats["accel"] = {
            {"kind", name_of(world.accelerator().kind())},
            {"build_seconds", world.build_seconds()},
            {"memory_bytes", world.accelerator().memory_bytes()},
            {"nodes", world.accelerator().node_count()},
            {"nodes_visited_per_ray", static_cast<double>(counts.nodes) / queries},
            {"primitives_tested_per_ray", static_cast<double>(counts.primitives) / queries}};
        if (settings.mode == Mode::hybrid) {
            stats["hybrid"] = {{"gl", args.frame.gl},
                               {"gl_renderer", frame.gl_renderer},
                               {"raster", args.frame.raster},
                               {"tessellation", args.frame.tessellation},
                               {"resolve", args.frame.resolve},
                               {"exact_intersections", frame.primary_stats.exact_intersections},
                               {"fallbacks", frame.primary_stats.fallbacks},
                               {"corrected", frame.primary_stats.corrected},
                               {"edges", frame.primary_stats.edges},
                               {"max_deviation", frame.deviations.empty()
                                                     ? 0.0f
                                                     : *std::max_element(frame.deviations.begin(),
                                                                         frame.deviations.end())}};
        }
        write_file_atomically(args.stats, stats.dump(2) + "\n");
    }
    std::printf("glint: wrote %s (%dx%d, %s, %s, %d threads) in %.3f s (render %.3f s)\n",
                output.c_str(), scene.camera.width, scene.camera.height,
                args.frame.describe().c_str(),
                std::string(name_of(world.accelerator().kind())).c_str(), threads, total_seconds,
                t.total());
    std::printf("rays: %llu primary, %llu shadow, %llu reflection\n",
                static_cast<unsigned long long>(rays.primary),
                static_cast<unsigned long long>(rays.shadow),
                static_cast<unsigned long long>(rays.reflection));
    if (cutoff.largest_omitted_weight == 0)
        std::printf("reflection cut-off: no reflection ray omitted\n");
    else
        // A worst case from the brightest the scene could be (trace/cutoff.h), not a measured
        // error: said so, since a large bound on a bright mirror scene is usual, not an alarm.
        std::printf("reflection cut-off (max depth %d, min reflectivity %g): reflections not "
                    "followed could make %llu pixels brighter by more than 1/255, none by more "
                    "than %d/255 (a worst-case bound, not a measured error; heaviest omitted path "
                    "weight %.3g)\n",
                    scene.render.max_depth, static_cast<double>(scene.render.min_reflectivity),
                    static_cast<unsigned long long>(cutoff.pixels_over_one), cutoff.max,
                    cutoff.largest_omitted_weight);
    return 0;
}

} // namespace

Command add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene to a PNG file");
    args->scene.add_to(*cmd);
    cmd->add_option("-o,--output", args->output, "Output PNG; default out/<scene name>.png");
    args->frame.add_to(*cmd, true);
    cmd->add_option("--stats", args->stats,
                    "Also write timings per phase and ray counts as JSON here");
    return {cmd, [args] { prepare(*args); },
            [args] { return guarded([&] { return run_render(*args); }); }};
}

} // namespace glint
