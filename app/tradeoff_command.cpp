// `glint tradeoff`: sweeps the knobs that trade speed for accuracy, one at a time from the
// default setting, timing each run side by side in one process and comparing its image with the
// exact one: ray traced in double precision, reflections followed as deep as glint allows with
// no weight cut-off. Writes a CSV (a row per run), a plot per scene of time against error with
// the Pareto front (gnuplot, SVG and PNG) and a markdown summary (docs/TRADEOFF.md).
#include "app/distributed.h"
#include "app/options.h"
#include "app/rank_records.h"
#include "app/tradeoff.h"

#include "io/error.h"
#include "io/write_file.h"
#include "trace/cutoff.h"
#include "trace/stopwatch.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

namespace glint {
namespace {

using namespace tradeoff;

std::vector<fs::path> scene_paths(const TradeoffArgs& args) {
    std::vector<fs::path> paths(args.scenes.begin(), args.scenes.end());
    if (paths.empty()) {
        const fs::path dir = fs::exists("scenes/default.json")
                                 ? fs::path("scenes")
                                 : fs::path(GLINT_SOURCE_DIR) / "scenes";
        for (const fs::directory_entry& entry : fs::directory_iterator(dir))
            if (entry.path().extension() == ".json") paths.push_back(entry.path());
        std::sort(paths.begin(), paths.end());
    }
    return paths;
}

// Every check on the input before any rendering: scenes load, size and outputs are usable.
std::vector<SceneResult> prepare(const TradeoffArgs& args) {
    const fs::path out = args.output;
    std::error_code ec;
    if (rank() == 0) { // only rank 0 writes
        if (fs::exists(out, ec) && !fs::is_directory(out, ec))
            throw UsageError("-o " + out.string() + ": is not a directory");
        check_output(fs::is_directory(out, ec) ? out / "tradeoff.csv" : out, "-o");
        if (!args.summary.empty()) check_output(args.summary, "--summary"); // else inside -o
    }
    std::vector<SceneResult> results;
    for (const fs::path& path : scene_paths(args)) {
        ModelOptions model;
        if (!args.size.empty()) model.size = parse_size(args.size, "--size");
        SceneResult sr{
            path.stem().string(), path, load_scene_with_notes(path, model), {}, {}, 0, 0};
        // The exact image, its float twin and the run being measured are alive together, and
        // the antialiasing runs draw an item buffer of --samples² samples a pixel.
        Scene sampled = sr.scene;
        sampled.render.samples = args.samples;
        check_frame_memory(sampled, Mode::hybrid, 3);
        results.push_back(std::move(sr));
    }
    return results;
}

// The command's steps in their order: checks, then per scene the exact image and the sweep, then
// CSV, plots and summary, kept whole so that the order reads as it runs.
int run_tradeoff(const TradeoffArgs& args) {
    const Stopwatch watch;
    std::vector<SceneResult> results;
    // On ranks, every rank checks its input (rank 0 also where it writes) and they agree.
    if (const int status = agree_on([&] {
            results = prepare(args);
            if (rank() == 0 && std::system("command -v gnuplot >/dev/null 2>&1") != 0)
                throw std::runtime_error("glint tradeoff plots with gnuplot, which is not "
                                         "installed (apt install gnuplot-nox; ./glint tradeoff "
                                         "installs it)");
        }))
        return status;
    const fs::path out = args.output;
    if (rank() == 0) fs::create_directories(out);
    const fs::path summary = args.summary_path();
    const fs::path plots = fs::relative(fs::absolute(out), fs::absolute(summary).parent_path());
    std::string gl_renderer = "none";

    for (SceneResult& sr : results) {
        const Scene& scene = sr.scene;
        Scene deep = scene;
        deep.render = {kMaxDepth, 0.0f};
        // The scene's meshes and materials, prepared once for the float renders of its sweep.
        const auto geometry = std::make_shared<const SceneGeometry>(scene);
        FrameSettings deep_ray;
        deep_ray.mode = Mode::ray;
        deep_ray.threads = args.threads;
        deep_ray.precision = Precision::f64;
        // Kept as a side of each run's comparison, whose differing pixels it traces again.
        const RenderedSide exact({"exact", deep, std::nullopt, deep_ray});
        const Frame& reference = exact.frame();
        sr.reference_seconds = reference.times.total();
        sr.reference_bound = cutoff_bound(deep, reference.result);
        deep_ray.precision = Precision::f32;
        const Image untruncated_float =
            render_frame(deep, std::nullopt, deep_ray, nullptr, geometry).result.bytes();

        // The antialiasing knobs' reference: the default setting's uniform 8×8 image, ray traced.
        Setting grid_setting;
        grid_setting.frame.mode = Mode::ray;
        grid_setting.max_depth = scene.render.max_depth;
        grid_setting.min_reflectivity = scene.render.min_reflectivity;
        grid_setting.samples = kGridReference;
        Run grid_run = render_once(scene, grid_setting, args, geometry);
        sr.grid_seconds = grid_run.total_seconds();
        const RenderedSide grid(side_of(scene, grid_setting, args), std::move(grid_run.frame),
                                geometry);

        // The settings, each label once (a label several sweeps reach gathers their knobs); on
        // MPI ranks, setting k is measured by rank k mod ranks and its figures sent to rank 0.
        const auto settings = sweep(scene, args.samples);
        std::map<std::string, std::size_t> seen;
        for (const auto& [knob, setting] : settings) {
            const std::string label = setting.label(scene);
            if (const auto it = seen.find(label); it != seen.end()) {
                sr.runs[it->second].knobs += "+" + knob;
                continue;
            }
            seen[label] = sr.runs.size();
            Run& run = sr.runs.emplace_back();
            run.knobs = knob, run.label = label, run.setting = setting;
        }
        if (rank() == 0)
            std::printf("%s (%dx%d): %zu settings%s\n", sr.name.c_str(), scene.camera.width,
                        scene.camera.height, sr.runs.size(),
                        on_ranks() ? (" over " + std::to_string(ranks()) + " ranks").c_str() : "");
        std::vector<RunFigures> figures;
        for (std::size_t k = static_cast<std::size_t>(rank()); k < sr.runs.size();
             k += static_cast<std::size_t>(ranks())) {
            const Setting& setting = sr.runs[k].setting;
            Run run = measure(scene, setting, args, geometry);
            const RenderResult& result = run.frame.result;
            const RenderedSide& against = setting.against_grid ? grid : exact;
            run.diff = compare_results(against.frame().result, result);
            run.causes = cause_figures(why_it_differs(scene, against, run, args, geometry));
            if (setting.divisor == 1 && !setting.against_grid)
                run.agreement = id_agreement(reference.result.ids, result.ids);
            if (setting.frame.precision == Precision::f32 && setting.frame.mode == Mode::ray &&
                setting.divisor == 1)
                run.bound_held =
                    cutoff_violations(run.bound, result.bytes(), untruncated_float) == 0;
            if (!result.refined.empty())
                run.refined = static_cast<std::uint64_t>(
                    std::count(result.refined.begin(), result.refined.end(), 1));
            run.pixels = result.refined.size();
            if (!run.frame.gl_renderer.empty()) gl_renderer = run.frame.gl_renderer;
            figures.push_back(figures_of(run));
            run.knobs = sr.runs[k].knobs, run.label = sr.runs[k].label;
            if (!on_ranks())
                std::printf("  %-44s %8.4f s  PSNR %6s dB  max error %3d/255\n", run.label.c_str(),
                            run.frame_seconds(), psnr_text(run.diff.psnr_db).c_str(),
                            run.diff.max_abs_error);
            std::fflush(stdout);
            sr.runs[k] = std::move(run);
        }
        if (on_ranks()) {
            const std::vector<std::vector<RunFigures>> all = gather_records(figures);
            if (rank() != 0) continue;
            for (int r = 1; r < ranks(); ++r) {
                const RunFigures* f = all[static_cast<std::size_t>(r)].data();
                for (std::size_t k = static_cast<std::size_t>(r); k < sr.runs.size();
                     k += static_cast<std::size_t>(ranks()), ++f) {
                    Run run = run_from_figures(*f);
                    run.knobs = sr.runs[k].knobs, run.label = sr.runs[k].label;
                    run.setting = sr.runs[k].setting;
                    sr.runs[k] = std::move(run);
                }
            }
            for (const Run& run : sr.runs)
                std::printf("  %-44s %8.4f s  PSNR %6s dB  max error %3d/255\n", run.label.c_str(),
                            run.frame_seconds(), psnr_text(run.diff.psnr_db).c_str(),
                            run.diff.max_abs_error);
        }
        if (rank() == 0) budget_thumbnails(sr, exact, args, geometry, out);
        // Two plots: the knobs against the exact image, and antialiasing against 8×8.
        std::vector<Run> exact_runs, grid_runs;
        for (Run& r : sr.runs) (r.setting.against_grid ? grid_runs : exact_runs).push_back(r);
        plot(sr.name, exact_runs, out, "the exact image");
        plot(sr.name + "-antialiasing", grid_runs, out, "the uniform 8x8 image");
    }
    if (rank() != 0) return 0;
    write_csv(results, out / "tradeoff.csv");
    write_file_atomically(summary, markdown(results, args, plots, gl_renderer, watch.seconds()));
    std::printf("wrote %s, %s and a plot per scene (SVG, PNG) in %s, in %.0f s\n",
                (out / "tradeoff.csv").c_str(), summary.c_str(), out.c_str(), watch.seconds());
    return 0;
}

} // namespace

Command add_tradeoff_command(CLI::App& app) {
    auto args = std::make_shared<TradeoffArgs>();
    CLI::App* cmd = app.add_subcommand(
        "tradeoff", "Sweep the speed/accuracy knobs against the exact image: CSV, plots, summary");
    cmd->add_option("scenes", args->scenes,
                    "Scene files (JSON or .nff); default every scene in scenes/");
    cmd->add_option("-o,--output", args->output, "Directory for tradeoff.csv and the plots")
        ->capture_default_str();
    cmd->add_option("--summary", args->summary, "Markdown summary; default OUTPUT/summary.md");
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT for every scene");
    cmd->add_option("--repeat", args->repeat, "Renders per setting; the median time is kept")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    cmd->add_option("--gl", args->gl, "Headless GL for the item buffer: osmesa or egl")
        ->capture_default_str()
        ->check(CLI::IsMember(all_names<GlBackend>()));
    cmd->add_option("--threads", args->threads, "Worker threads; default all cores")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--samples", args->samples,
                    "Antialiasing knobs: uniform grids 1 to N, and adaptive at NxN, each against "
                    "the uniform 8x8 image")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxSamples));
    return {cmd, [args] { prepare(*args); },
            [args] { return guarded_on_ranks([&] { return run_tradeoff(*args); }); }};
}

} // namespace glint
