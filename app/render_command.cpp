// `glint render`: load, prepare, trace, write; every failure becomes a one-line message.
#include "app/commands.h"
#include "app/progress.h"

#include "trace/image.h"
#include "trace/render.h"
#include "trace/scene_loader.h"

#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <regex>

namespace glint {
namespace {

namespace fs = std::filesystem;

// Bad command-line input: exit code 2.
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string mode = "ray";
    std::string size;
    int max_depth = 0;
    double min_reflectivity = 0;
    int threads = 0;
    std::string stats;
    CLI::Option* max_depth_option = nullptr;
    CLI::Option* min_reflectivity_option = nullptr;
};

fs::path default_scene() {
    const fs::path local = "scenes/default.json";
    if (fs::exists(local)) return local;
    return fs::path(GLINT_SOURCE_DIR) / local; // glint run from outside its checkout
}

// An output file must be creatable: its directory exists and it is not itself a directory.
void check_output(const fs::path& path, const std::string& flag) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : ".";
    if (!fs::is_directory(dir))
        throw UsageError(flag + " " + path.string() + ": directory " + dir.string() +
                         " does not exist");
    if (fs::is_directory(path)) throw UsageError(flag + " " + path.string() + ": is a directory");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run_render(const RenderArgs& args) {
    const auto start = std::chrono::steady_clock::now();
    if (args.mode == "hybrid")
        throw UsageError("--mode hybrid needs the item buffer (OpenGL), which this build does not "
                         "have yet; use --mode ray");
    const fs::path scene_path = args.scene.empty() ? default_scene() : fs::path(args.scene);
    fs::path output = args.output;
    if (output.empty()) {
        output = fs::path("out") / scene_path.stem().concat(".png");
        fs::create_directories(output.parent_path());
    }
    if (output.extension() != ".png")
        throw UsageError("-o " + output.string() + ": glint writes PNG files (.png)");
    check_output(output, "-o");
    if (!args.stats.empty()) check_output(args.stats, "--stats");

    Scene scene = load_scene(scene_path);
    if (!args.size.empty()) {
        static const std::regex size_pattern(R"((\d{1,5})x(\d{1,5}))");
        std::smatch m;
        if (!std::regex_match(args.size, m, size_pattern))
            throw UsageError("--size " + args.size + ": expected WIDTHxHEIGHT, e.g. 800x600");
        const int w = std::stoi(m[1]), h = std::stoi(m[2]);
        if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
            throw UsageError("--size " + args.size + ": each side must be 1 to " +
                             std::to_string(kMaxImageSide));
        scene.camera.width = w, scene.camera.height = h;
    }
    if (args.max_depth_option->count()) scene.render.max_depth = args.max_depth;
    if (args.min_reflectivity_option->count())
        scene.render.min_reflectivity = static_cast<float>(args.min_reflectivity);
    const double load_seconds = seconds_since(start);

    const auto prepare_start = std::chrono::steady_clock::now();
    const World world(scene);
    const double prepare_seconds = seconds_since(prepare_start);

    const auto render_start = std::chrono::steady_clock::now();
    std::atomic<int> tiles_done{0};
    RenderResult result;
    {
        const Progress progress("rendering", tile_count(scene.camera.width, scene.camera.height),
                                tiles_done);
        result = render(world, {args.threads, &tiles_done});
    }
    const double render_seconds = seconds_since(render_start);

    const auto write_start = std::chrono::steady_clock::now();
    write_png(output, result.image);
    const double write_seconds = seconds_since(write_start);
    const double total_seconds = seconds_since(start);
    const int threads = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();

    const RayCounts& rays = result.rays;
    if (!args.stats.empty()) {
        const nlohmann::ordered_json stats = {
            {"scene", scene_path.string()},
            {"output", output.string()},
            {"width", scene.camera.width},
            {"height", scene.camera.height},
            {"mode", args.mode},
            {"threads", threads},
            {"max_depth", scene.render.max_depth},
            {"min_reflectivity", scene.render.min_reflectivity},
            {"seconds",
             {{"load", load_seconds},
              {"prepare", prepare_seconds},
              {"render", render_seconds},
              {"write", write_seconds},
              {"total", total_seconds}}},
            {"rays",
             {{"primary", rays.primary}, {"shadow", rays.shadow}, {"reflection", rays.reflection}}},
        };
        write_file_atomically(args.stats, stats.dump(2) + "\n");
    }
    std::printf("glint: wrote %s (%dx%d, %s mode, %d threads) in %.3f s (render %.3f s)\n",
                output.c_str(), scene.camera.width, scene.camera.height, args.mode.c_str(), threads,
                total_seconds, render_seconds);
    std::printf("rays: %llu primary, %llu shadow, %llu reflection\n",
                static_cast<unsigned long long>(rays.primary),
                static_cast<unsigned long long>(rays.shadow),
                static_cast<unsigned long long>(rays.reflection));
    return 0;
}

// Runs a command body, turning exceptions into glint's exit codes and one-line messages.
int guarded(const std::function<int()>& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 2;
    } catch (const SceneError& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 1;
    }
}

} // namespace

Command add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene to a PNG file");
    cmd->add_option("scene", args->scene, "Scene file (JSON); default scenes/default.json");
    cmd->add_option("-o,--output", args->output, "Output PNG; default out/<scene name>.png");
    cmd->add_option("--mode", args->mode,
                    "Primary visibility: ray (hybrid arrives with the item buffer)")
        ->check(CLI::IsMember({"ray", "hybrid"}));
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT, overriding the scene's camera");
    args->max_depth_option =
        cmd->add_option("--max-depth", args->max_depth, "Maximum reflection depth (0 = none)")
            ->check(CLI::Range(0, kMaxDepth));
    args->min_reflectivity_option =
        cmd->add_option("--min-reflectivity", args->min_reflectivity,
                        "Smallest path weight for which a reflection ray is still cast")
            ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--threads", args->threads, "Worker threads; default all cores")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--stats", args->stats, "Also write timings and ray counts as JSON here");
    return {cmd, [args] { return guarded([&] { return run_render(*args); }); }};
}

} // namespace glint
