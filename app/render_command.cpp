// `glint render`: load, prepare, draw the item buffer (hybrid), trace, write.
#include "app/distributed.h"
#include "app/options.h"
#include "app/progress.h"
#include "app/render_stats.h"
#include "frame/gl_pass.h"
#include "frame/record_json.h"

#include "io/exr.h"
#include "io/scene_check.h"
#include "io/extension.h"
#include "io/png.h"
#include "io/write_file.h"
#include "trace/cutoff.h"
#include "trace/frame_records.h"
#include "trace/image.h"
#include "trace/kernel.h"
#include "trace/stopwatch.h"

#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <memory>
#include <optional>

namespace glint {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
    SceneOptions scene;
    FrameOptions frame;
    std::string output;
    std::string stats;
    std::string aa_map;
    std::vector<std::string> aovs;
    // A sequence (DESIGN §13): `--frames N` at `--fps F`, from --time (default 0), optionally
    // orbiting the camera; written to a pattern with a number field (`-o out/x-%04d.png`).
    std::string colour = "linear"; // --colour: linear (DESIGN §11's bytes) or srgb
    int frames = 1;
    double fps = 24;
    bool orbit = false;
    CLI::Option* frames_option = nullptr;
    CLI::Option* fps_option = nullptr;
    bool sequence() const { return frames_option->count() > 0 || orbit; }
};

// An output pattern's number field: printf's %d, %Nd or %0Nd (N at most 9), the one '%' the
// name may hold besides "%%"; nothing where it has none.
struct NumberField {
    std::size_t at = 0, length = 0;
    std::string format; // "%04d"
};

std::optional<NumberField> number_field(const std::string& pattern) {
    std::optional<NumberField> found;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') continue;
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        while (j < pattern.size() && j - i <= 2 && std::isdigit(static_cast<unsigned char>(pattern[j])))
            ++j;
        if (j >= pattern.size() || pattern[j] != 'd' || found)
            throw UsageError("-o " + pattern + ": a sequence's name holds one number field, %d, "
                             "%4d or %04d (write %% for a percent sign)");
        found = NumberField{i, j + 1 - i, pattern.substr(i, j + 1 - i)};
        i = j;
    }
    return found;
}

// Frame k's file name: the pattern with its number field filled and "%%" made '%'.
fs::path frame_path(const std::string& pattern, int k) {
    const std::optional<NumberField> field = number_field(pattern);
    std::string name;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (field && i == field->at) {
            char number[32];
            std::snprintf(number, sizeof number, field->format.c_str(), k);
            name += number;
            i += field->length - 1;
        } else {
            name += pattern[i];
            if (pattern[i] == '%' && i + 1 < pattern.size() && pattern[i + 1] == '%') ++i;
        }
    }
    return name;
}


// What a render needs once its input has been checked.
struct RenderJob {
    fs::path scene_path;
    fs::path output;
    Scene scene;
    std::vector<Aov> aovs; // EXR only
    bool srgb = false;     // --colour srgb
    std::string pattern;   // a sequence's output names, with a number field (or the one name)
};

// Every check on the input, before anything is rendered or written. On MPI ranks only rank 0
// writes, so only rank 0 checks where it writes; every rank reads the scene.
RenderJob prepare(const RenderArgs& args) {
    RenderJob job{args.scene.scene_path(), args.output, {}, {}, args.colour == "srgb", {}};
    if (job.output.empty())
        job.output = fs::path("out") /
                     job.scene_path.stem().concat(args.sequence() && args.frames > 1 ? "-%04d.png"
                                                                                      : ".png");
    if (args.sequence()) {
        if (args.frames < 1)
            throw UsageError("--frames " + std::to_string(args.frames) + ": must be 1 or more");
        if (!(args.fps > 0 && args.fps <= 1e6))
            throw UsageError("--fps " + args.fps_option->as<std::string>() +
                             ": must be above 0 (frames a second, at most 1e6)");
        if (!args.stats.empty() || !args.aa_map.empty())
            throw UsageError(std::string(args.stats.empty() ? "--aa-map" : "--stats") +
                             " describes one frame: not with --frames or --orbit");
        job.pattern = job.output.string();
        if (!number_field(job.pattern) && args.frames > 1)
            throw UsageError("-o " + job.pattern + ": --frames " + std::to_string(args.frames) +
                             " needs a number field in the name, as out/frame-%04d.png");
        job.output = frame_path(job.pattern, 0);
    }
    const std::string format = extension_of(job.output); // x.PNG is a PNG, as scenes' names go
    if (format != ".png" && format != ".exr")
        throw UsageError("-o " + job.output.string() +
                         ": glint writes PNG (.png) and OpenEXR (.exr) files");
    job.aovs = parse_aovs(args.aovs);
    if (!job.aovs.empty() && format != ".exr")
        throw UsageError("--aov " + args.aovs.front() +
                         ": AOVs are channels of an OpenEXR file; give -o FILE.exr");
    if (!args.aa_map.empty() && extension_of(args.aa_map) != ".png")
        throw UsageError("--aa-map " + args.aa_map + ": glint writes PNG files (.png)");
    if (rank() == 0) {
        if (args.output.empty()) create_output_directory(job.output);
        check_output(job.output, "-o");
        if (!args.stats.empty()) check_output(args.stats, "--stats");
        if (!args.aa_map.empty()) check_output(args.aa_map, "--aa-map");
    }
    SceneOptions scene = args.scene;
    scene.animate = args.sequence();
    scene.srgb = args.colour == "srgb";
    job.scene = scene.load();
    if (!args.aa_map.empty() &&
        (job.scene.render.samples == 1 || job.scene.render.antialias != Antialias::adaptive))
        throw UsageError("--aa-map " + args.aa_map +
                         ": maps adaptive antialiasing; give --aa adaptive and --samples N > 1 "
                         "(or a scene with them)");
    check_frame_memory(job.scene, args.frame.settings().mode, 1);
    return job;
}

// The lines every render prints: where it wrote and how long it took, the rays, the cut-off.
void print_report(const RenderReport& r) {
    const Scene& scene = r.scene;
    const RayCounts& rays = r.frame.result.rays;
    std::printf("glint: wrote %s (%dx%d, %s, %s, %d threads) in %.3f s (render %.3f s)\n",
                r.output.c_str(), scene.camera.width, scene.camera.height,
                r.frame_options.describe().c_str(),
                std::string(name_of(r.world.accelerator().kind())).c_str(), r.threads,
                r.total_seconds, r.frame.times.total());
    if (const std::string aa = describe_antialiasing(scene.render); !aa.empty()) {
        std::printf("antialiasing: %s", aa.c_str());
        const std::vector<std::uint8_t>& refined = r.frame.result.refined;
        if (!refined.empty()) {
            const auto count = std::count(refined.begin(), refined.end(), std::uint8_t{1});
            std::printf(": %lld of %zu pixels took the grid (%.1f%%)",
                        static_cast<long long>(count), refined.size(),
                        100.0 * static_cast<double>(count) / static_cast<double>(refined.size()));
        }
        std::printf("\n");
    }
    std::printf("rays: %llu primary, %llu shadow, %llu reflection",
                static_cast<unsigned long long>(rays.primary),
                static_cast<unsigned long long>(rays.shadow),
                static_cast<unsigned long long>(rays.reflection));
    if (rays.transmission > 0)
        std::printf(", %llu transmission", static_cast<unsigned long long>(rays.transmission));
    std::printf("\n");
    if (r.cutoff.largest_omitted_weight == 0)
        std::printf("reflection cut-off: no reflection ray omitted\n");
    else
        // A worst case from the brightest the scene could be (trace/cutoff.h), not a measured
        // error: said so, since a large bound on a bright mirror scene is usual, not an alarm.
        std::printf("reflection cut-off (max depth %d, min reflectivity %g): secondary rays "
                    "not followed could make %llu pixels brighter by more than 1/255, none by more "
                    "than %d/255 (a worst-case bound, not a measured error; largest omitted weight "
                    "in a pixel %.3g)\n",
                    scene.render.max_depth, static_cast<double>(scene.render.min_reflectivity),
                    static_cast<unsigned long long>(r.cutoff.pixels_over_one), r.cutoff.max,
                    r.cutoff.largest_omitted_weight);
}

// Where adaptive antialiasing took the grid: those pixels as rendered, the rest at a quarter of
// their brightness.
Image refinement_map(const RenderResult& result) {
    Image map = result.bytes();
    for (std::size_t i = 0; i < result.refined.size(); ++i)
        if (!result.refined[i])
            for (int c = 0; c < 3; ++c) map.rgb[3 * i + c] /= 4;
    return map;
}

bool wants(const std::vector<Aov>& aovs, Aov aov) {
    return std::find(aovs.begin(), aovs.end(), aov) != aovs.end();
}

// Whether writing `job`'s frames reads their float images: not for a linear PNG, which is the
// display bytes, as is all its report reads. A frame of those alone
// (RenderResult::display_bytes) first touches 6 MB at 1920×1080 where its floats are 25.
bool reads_floats(const RenderJob& job) {
    return extension_of(job.output) != ".png" || job.srgb;
}

// The frame as the output's format: the PNG's bytes (through the sRGB curve with --colour srgb),
// or the EXR's float image with its AOVs (linear either way).
void write_image(const RenderJob& job, const RenderResult& result) {
    if (extension_of(job.output) == ".png") {
        // A frame made as the PNG's bytes (linear colour) is written as it is.
        if (!result.floats()) return write_png(job.output, result.display_bytes);
        // Rows quantised as they are deflated: no 8-bit copy of the frame.
        const FloatImage& display = result.display();
        return write_png(job.output, display.width, display.height,
                         [&](int y, std::uint8_t* out) { row_bytes(display, y, job.srgb, out); });
    }
    const std::vector<float> cutoff =
        wants(job.aovs, Aov::cutoff) ? cutoff_radiance(job.scene, result) : std::vector<float>();
    ExrLayers layers{&result.radiance};
    if (wants(job.aovs, Aov::depth)) layers.depth = &result.aovs.depth;
    if (wants(job.aovs, Aov::normal)) layers.normal = &result.aovs.normal;
    if (wants(job.aovs, Aov::id)) layers.id = &result.aovs.id;
    if (wants(job.aovs, Aov::cutoff)) layers.cutoff = &cutoff;
    write_exr(job.output, layers);
}

// Several ranks: every rank's figures on rank 0 (returned there; empty elsewhere), and the
// frame's counters summed over ranks (each rank counted its own tiles' rays and resolves).
// Prints the per-rank table.
std::vector<RankFigures> combine_ranks(Frame& frame, const RankFigures& mine, int threads) {
    FrameCounters counters{frame.result.rays, frame.primary_stats};
    sum_over_ranks(counters);
    frame.result.rays = counters.rays, frame.primary_stats = counters.primary;
    std::vector<RankFigures> all = gather_figures(mine);
    if (rank() != 0) return all;
    std::printf("ranks: %d × %d threads, tiles claimed as ranks ask, each pass's pixels gathered "
                "on rank 0\n",
                ranks(), threads);
    constexpr double MB = 1e6;
    for (std::size_t r = 0; r < all.size(); ++r) {
        const RankFigures& f = all[r];
        const PassExchange x = f.exchange();
        std::printf(
            "  rank %zu: %llu tiles (all passes), %.2f M rays; load %.3f s, structures %.3f s, "
            "GL %.3f s, trace %.3f s, exchange %.3f s (%.2f MB sent, %.2f MB received)\n",
            r, static_cast<unsigned long long>(f.tiles), static_cast<double>(f.rays) / 1e6,
            f.load, f.prepare, f.gl, f.trace, x.seconds, static_cast<double>(x.sent) / MB,
            static_cast<double>(x.received) / MB);
        for (const FramePass pass : {FramePass::centres, FramePass::grids, FramePass::spread}) {
            const PassExchange& p = all[r].after(pass);
            if (p.exchanges == 0) continue;
            std::printf("    after %s: %llu exchange%s, %.3f s, %.2f MB sent, %.2f MB received\n",
                        std::string(name_of(pass)).c_str(),
                        static_cast<unsigned long long>(p.exchanges), p.exchanges == 1 ? "" : "s",
                        p.seconds, static_cast<double>(p.sent) / MB,
                        static_cast<double>(p.received) / MB);
        }
    }
    return all;
}

// A sequence: the scene loaded, its meshes, BVHs and textures prepared, and the GL context and
// shaders made once; per frame, the animation's pose and the orbit's camera, a World over the
// shared geometry (its top-level structure built anew), the item buffer uploaded and drawn,
// the frame traced and written.
//
// Under mpirun the frames are spread over the ranks, frame k on rank k mod ranks: each rank
// renders its frames whole, with every core it has, and writes them itself (no exchange); every
// rank has checked the input before any renders.
int run_sequence(const RenderArgs& args) {
    const Stopwatch total;
    RenderJob job;
    if (const int status = agree_on([&] { job = prepare(args); })) return status;
    const std::string who = on_ranks() ? "rank " + std::to_string(rank()) + ": " : "";
    Scene& scene = job.scene;
    const Camera unorbited = scene.camera;
    FrameSettings settings = args.frame.settings();
    settings.radiance = reads_floats(job);
    std::optional<GlPass> gl;
    if (needs_gl(settings, scene.objects.size())) gl.emplace(settings);
    const Stopwatch prepare_watch;
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const double prepare_seconds = prepare_watch.seconds();
    char moving[256] = "no animation";
    if (scene.animation)
        std::snprintf(moving, sizeof moving, "%s, %g s", scene.animation->name().c_str(),
                      scene.animation->duration());
    if (rank() == 0)
        std::printf("glint: %d frame%s of %s at %g fps from t = %g s (%s%s)%s\n", args.frames,
                    args.frames == 1 ? "" : "s", job.scene_path.c_str(), args.fps,
                    args.scene.time, moving, args.orbit ? ", orbiting" : "",
                    on_ranks() ? (", frame k on rank k mod " + std::to_string(ranks())).c_str()
                               : "");
    std::printf("%smeshes, BVHs and textures prepared once in %.3f s\n", who.c_str(),
                prepare_seconds);
    std::fflush(stdout);
    double traced = 0, posing = 0, structures = 0;
    int written = 0;
    for (int k = rank(); k < args.frames; k += ranks()) {
        const Stopwatch frame_watch;
        const double t = args.scene.time + k / args.fps;
        if (scene.animation && k > 0) {
            Stopwatch phase;
            scene.animation->pose(scene, t);
            // A pose may scale a node to nothing: held to the scene's rules, frame by frame.
            check_scene(scene, [&](const std::string& path) {
                return job.scene_path.string() + " at t = " + std::to_string(t) + " s: /" + path;
            });
            posing += phase.lap();
            // Skinned and morphed meshes moved: their BVHs are built again, the rest kept.
            geometry = SceneGeometry::posed(geometry, scene);
            structures += phase.lap();
        }
        if (args.orbit) scene.camera = orbit_camera(unorbited, k, args.frames);
        const Stopwatch world_watch;
        const World world(scene, geometry, args.scene.accel_kind());
        structures += world_watch.seconds();
        std::atomic<int> tiles_done{0};
        Frame frame;
        {
            // A long frame shows its tiles as a single render does (a terminal only).
            const Progress progress(
                who + "frame " + std::to_string(k + 1) + "/" + std::to_string(args.frames),
                progress_steps(scene.render, scene.camera.width, scene.camera.height), tiles_done);
            frame = render_frame(world, settings, &tiles_done, gl ? &*gl : nullptr);
        }
        traced += frame.times.total();
        job.output = frame_path(job.pattern, k);
        write_image(job, frame.result);
        ++written;
        std::printf("%sframe %d/%d (t = %.4g s): wrote %s in %.3f s\n", who.c_str(), k + 1,
                    args.frames, t, job.output.c_str(), frame_watch.seconds());
        std::fflush(stdout);
    }
    std::printf("%sglint: wrote %d frame%s (%dx%d, %s) in %.3f s (pose %.3f s, structures "
                "%.3f s, render %.3f s)\n",
                who.c_str(), written, written == 1 ? "" : "s", scene.camera.width,
                scene.camera.height, args.frame.describe().c_str(), total.seconds(), posing,
                structures, traced);
    return 0;
}

int run_render(const RenderArgs& args) {
    if (args.sequence()) return run_sequence(args);
    const Stopwatch total;
    Stopwatch phase;
    RenderJob job;
    // On ranks, every rank checks its input and they agree before any of them renders.
    if (const int status = agree_on([&] { job = prepare(args); })) return status;
    const Scene& scene = job.scene;
    const double load_seconds = phase.lap();
    FrameSettings settings = args.frame.settings();
    // Hybrid: the GL pass makes its context and shaders on its own thread while the World is
    // built here (frame/gl_pass.h).
    std::optional<GlPass> gl;
    if (needs_gl(settings, scene.objects.size())) gl.emplace(settings);
    World world(scene, args.scene.accel_kind());
    if (!args.stats.empty()) world.count_traversals(true);
    const double prepare_seconds = phase.lap();

    const int tiles = tile_count(scene.camera.width, scene.camera.height);
    const std::unique_ptr<TileExchange> exchange = on_ranks() ? make_exchange(tiles) : nullptr;
    settings.exchange = exchange.get();
    settings.aovs = wants(job.aovs, Aov::depth) || wants(job.aovs, Aov::normal) ||
                    wants(job.aovs, Aov::id);
    settings.ids = false; // nothing here reads them (ranks keep them for the exchange)
    settings.radiance = reads_floats(job);
    std::atomic<int> tiles_done{0};
    Frame frame;
    {
        // Primary hits and shading each visit every tile once (adaptive antialiasing: twice);
        // on ranks, rank 0 shows its own share.
        const int steps =
            progress_steps(scene.render, scene.camera.width, scene.camera.height) / ranks();
        const std::optional<Progress> progress =
            rank() == 0 ? std::optional<Progress>(std::in_place, "rendering", steps, tiles_done)
                        : std::nullopt;
        frame = render_frame(world, settings, &tiles_done, gl ? &*gl : nullptr);
    }
    const int threads =
        args.frame.threads > 0 ? args.frame.threads : tbb::this_task_arena::max_concurrency();
    std::vector<RankFigures> rank_figures;
    if (on_ranks()) {
        // The passes time their own tracing: the GL context is made while the World is built,
        // so the frame's wall time less the GL's would not be the tracing.
        const PhaseTimes& t = frame.times;
        RankFigures mine;
        mine.load = load_seconds, mine.prepare = prepare_seconds;
        mine.gl = t.context + t.compile + t.upload + t.raster;
        exchange_figures(*exchange, mine);
        mine.trace = t.primary + t.shading; // the passes' own wall time: a loop's end not in it
        mine.tiles = static_cast<std::uint64_t>(exchange->tiles_taken());
        mine.rays = frame.result.rays.total();
        rank_figures = combine_ranks(frame, mine, threads);
        if (rank() != 0) return 0;
    }
    phase.restart();
    write_image(job, frame.result);
    const double write_seconds = phase.seconds();
    const double total_seconds = total.seconds();
    const RenderReport report{job.scene_path,
                              job.output,
                              scene,
                              args.frame,
                              world,
                              frame,
                              cutoff_summary(scene, frame.result),
                              threads,
                              load_seconds,
                              prepare_seconds,
                              write_seconds,
                              total_seconds,
                              rank_figures};
    if (!args.stats.empty()) write_file_atomically(args.stats, stats_json(report).dump(2) + "\n");
    if (!args.aa_map.empty()) write_png(args.aa_map, refinement_map(frame.result));
    print_report(report);
    return 0;
}

} // namespace

Command add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Render a scene to an image: PNG (8-bit) or OpenEXR (linear float)");
    args->scene.add_to(*cmd);
    cmd->add_option("-o,--output", args->output,
                    "Output image: .png (8-bit, clamped) or .exr (linear float, unclamped); "
                    "default out/<scene name>.png");
    add_aov_option(*cmd, args->aovs);
    args->frame.add_to(*cmd, true);
    args->frames_option =
        cmd->add_option("--frames", args->frames,
                        "Render a sequence of N frames at t = T + k/F (a glTF model's animation, "
                        "--orbit's turntable); -o then needs a number field, as out/x-%04d.png");
    args->fps_option =
        cmd->add_option("--fps", args->fps, "A sequence's frames a second")->capture_default_str();
    cmd->add_flag("--orbit", args->orbit,
                  "With --frames N: turn the camera 360° about the +Y axis through its look-at "
                  "point (a framed model's centre) over the N frames");
    add_colour_option(*cmd, args->colour);
    cmd->add_option("--stats", args->stats,
                    "Also write timings per phase and ray counts as JSON here");
    cmd->add_option("--aa-map", args->aa_map,
                    "Adaptive antialiasing: also write a PNG of the pixels that took the grid "
                    "(the others darkened)");
    return {cmd, [args] { prepare(*args); },
            [args] { return guarded_on_ranks([&] { return run_render(*args); }); }};
}

} // namespace glint
