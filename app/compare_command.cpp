// `glint compare`: the same scene in hybrid and ray mode in one run, phase by phase, with the
// ray image as the reference: id agreement, fallbacks, PSNR, maximum error, pixels off by > 1/255.
#include "app/compare.h"
#include "app/phase_json.h"
#include "frame/record_json.h"

#include "io/png.h"
#include "trace/frame_records.h"
#include "trace/image_metrics.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%9.4f", s);
    return text;
}

// Every check on the input, before anything is rendered or written; returns the scene.
Scene prepare(const CompareArgs& args) {
    if (args.exr)
        throw UsageError("--exr writes the float error of --a against --b: give the sides (e.g. "
                         "--a exact), or use `glint render -o NAME.exr` for one image");
    if (!args.prefix.empty()) check_output(args.prefix + "-ray.png", "-o");
    if (!args.json.empty()) check_output(args.json, "--json");
    Scene scene = args.scene.load();
    check_frame_memory(scene, Mode::hybrid, 2); // both frames are kept to compare them
    return scene;
}

// Both modes' frames of one scene and what sets them apart.
struct Comparison {
    const Scene& scene;
    const World& world;
    Frame ray, hybrid;
    ImageDifference diff;
    double agreement;     // fraction of pixels whose primary hits name the same object
    double primary_ratio; // primary visibility, hybrid / ray
    double frame_ratio;   // the whole frame, hybrid / ray
};

Comparison compare(const CompareArgs& args, const Scene& scene, const World& world) {
    FrameSettings settings = args.frame.settings();
    settings.mode = Mode::ray;
    Frame ray = render_frame(world, settings);
    settings.mode = Mode::hybrid;
    Frame hybrid = render_frame(world, settings);
    const ImageDifference diff = compare_results(ray.result, hybrid.result);
    const double agreement = id_agreement(ray.result.ids, hybrid.result.ids);
    // Per frame, the one-time set-up (context, shaders, upload) aside: what a preview pays again
    // for every frame. The whole-frame ratio counts everything a single render pays.
    const double primary_ratio = hybrid.times.primary_visibility() / ray.times.primary_visibility();
    const double frame_ratio = hybrid.times.total() / ray.times.total();
    return {scene, world,     std::move(ray), std::move(hybrid),
            diff,  agreement, primary_ratio,  frame_ratio};
}

void print_comparison(const CompareArgs& args, const Comparison& c) {
    const PhaseTimes &r = c.ray.times, &h = c.hybrid.times;
    const PrimaryStats& stats = c.hybrid.primary_stats;
    std::printf("glint compare: %s, %dx%d, %zu objects, %s, %s\n", args.scene.scene_path().c_str(),
                c.scene.camera.width, c.scene.camera.height, c.scene.objects.size(),
                args.frame.describe().c_str(),
                std::string(name_of(c.world.accelerator().kind())).c_str());
    if (const std::string aa = describe_antialiasing(c.scene.render); !aa.empty())
        std::printf("antialiasing: %s\n", aa.c_str());
    std::printf("GL: %s\n\n", c.hybrid.gl_renderer.c_str());
    std::printf("%-36s %9s %9s\n", "phase (seconds)", "ray", "hybrid");
    std::printf("%-36s %9s %s\n", "GL context creation", "-", seconds(h.context).c_str());
    std::printf("%-36s %9s %s\n", "shader compilation", "-", seconds(h.compile).c_str());
    std::printf("%-36s %9s %s\n", "tessellation and upload", "-", seconds(h.upload).c_str());
    std::printf("%-36s %9s %s\n", "rasterization + read-back", "-", seconds(h.raster).c_str());
    std::printf("%-36s %s %s\n", "primary rays (ray) / resolve (hybrid)",
                seconds(r.primary).c_str(), seconds(h.primary).c_str());
    std::printf("%-36s %s %s\n", "shading (shadow + reflection rays)", seconds(r.shading).c_str(),
                seconds(h.shading).c_str());
    std::printf("%-36s %s %s\n\n", "total", seconds(r.total()).c_str(), seconds(h.total()).c_str());
    std::printf("primary visibility, hybrid/ray:  %.3f  (raster + read-back + resolve vs. casting "
                "primary rays)\n",
                c.primary_ratio);
    std::printf("resolve / primary rays:          %.3f  (the exact resolve against a full primary "
                "trace)\n",
                h.primary / r.primary);
    std::printf(
        "whole frame, hybrid/ray:         %.3f  (including context, shaders and upload)\n\n",
        c.frame_ratio);
    std::printf("drawn as:            %zu proxies, %zu tessellations (the rest: planes, "
                "triangles, meshes)\n",
                c.hybrid.proxies, c.hybrid.tessellated);
    std::printf("id agreement:        %.4f%% of pixels name the same primary object\n",
                100 * c.agreement);
    std::printf("fallback pixels:     %llu (named object missed; traced in full)\n",
                static_cast<unsigned long long>(stats.fallbacks));
    std::printf("corrected pixels:    %llu (exact resolve found a nearer object)\n",
                static_cast<unsigned long long>(stats.corrected));
    std::printf("edge pixels:         %llu (ids change there: every object of the bin in front "
                "was a candidate)\n",
                static_cast<unsigned long long>(stats.edges));
    std::printf("checked pixels:      %llu (some other object survived the bins' culls; %.3f "
                "tests a pixel)\n",
                static_cast<unsigned long long>(stats.checked),
                static_cast<double>(stats.tests) / static_cast<double>(c.ray.result.ids.size()));
    std::printf("traced pixels:       %llu (traced in full: fallbacks, and a test hit in front)\n",
                static_cast<unsigned long long>(stats.traced));
    if (std::isinf(c.diff.psnr_db))
        std::printf("PSNR:                inf (identical images)\n");
    else
        std::printf("PSNR:                %.2f dB\n", c.diff.psnr_db);
    std::printf("max abs error:       %d/255\n", c.diff.max_abs_error);
    std::printf("pixels off > 1/255:  %.4f%% (%llu)\n", 100 * c.diff.fraction_over_one,
                static_cast<unsigned long long>(c.diff.pixels_over_one));
    std::printf("pixels off > 2/255:  %.4f%%\n", 100 * c.diff.fraction_over_two);
    std::printf("radiance error:      RMSE %.3g, largest %.3g (linear, unclamped)\n", c.diff.rmse,
                c.diff.max_radiance_error);
}

// --json: the same figures, for scripts (bench/crossover.py).
nlohmann::ordered_json comparison_json(const CompareArgs& args, const Comparison& c) {
    const PhaseTimes &r = c.ray.times, &h = c.hybrid.times;
    // The resolve's counters under their field names (trace/frame_records.h), in the "hybrid"
    // object as render's --stats writes them.
    nlohmann::ordered_json hybrid = {{"seconds", h.total()}, {"phases", phase_seconds_json(h)}};
    hybrid.update(record_json(c.hybrid.primary_stats));
    return {
        {"scene", args.scene.scene_path().string()},
        {"width", c.scene.camera.width},
        {"height", c.scene.camera.height},
        {"objects", c.scene.objects.size()},
        {"settings", args.frame.describe()},
        {"accel", name_of(c.world.accelerator().kind())},
        {"gl_renderer", c.hybrid.gl_renderer},
        {"ray", {{"seconds", r.total()}, {"phases", phase_seconds_json(r)}}},
        {"hybrid", hybrid},
        {"primary_ratio", c.primary_ratio},
        {"frame_ratio", c.frame_ratio},
        {"id_agreement", c.agreement},
        {"resolve_ratio", h.primary / r.primary},
        {"proxy_objects", c.hybrid.proxies},
        {"tessellated_objects", c.hybrid.tessellated},
        {"psnr_db", std::isinf(c.diff.psnr_db) ? nlohmann::ordered_json(nullptr)
                                               : nlohmann::ordered_json(c.diff.psnr_db)},
        {"max_abs_error", c.diff.max_abs_error},
        {"fraction_over_1_255", c.diff.fraction_over_one},
        {"fraction_over_2_255", c.diff.fraction_over_two},
        {"rmse_radiance", c.diff.rmse},
        {"max_error_radiance", c.diff.max_radiance_error},
        {"pixels", static_cast<double>(c.ray.result.ids.size())},
    };
}

int run_compare(const CompareArgs& args) {
    if (args.sides()) return run_compare_sides(args);
    const Scene scene = prepare(args);
    const World world(scene, args.scene.accel_kind());
    const Comparison c = compare(args, scene, world);
    print_comparison(args, c);
    if (!args.prefix.empty()) {
        const Image ray = c.ray.result.bytes(), hybrid = c.hybrid.result.bytes();
        write_png(args.prefix + "-ray.png", ray);
        write_png(args.prefix + "-hybrid.png", hybrid);
        write_png(args.prefix + "-diff.png", difference_heatmap(ray, hybrid));
        // What the item buffer drew at each pixel centre, or, with a uniform sample grid and
        // no centre pass, at each pixel's sample (N/2, N/2).
        std::vector<std::uint32_t> drawn;
        if (c.hybrid.items) {
            drawn = c.hybrid.items->ids.ids;
        } else if (c.hybrid.sample_items) {
            const IdImage& grid = c.hybrid.sample_items->ids;
            const int n = scene.render.samples;
            for (int y = 0; y < scene.camera.height; ++y)
                for (int x = 0; x < scene.camera.width; ++x)
                    drawn.push_back(grid.ids[static_cast<std::size_t>(y * n + n / 2) * grid.width +
                                             static_cast<std::size_t>(x * n + n / 2)]);
        }
        if (!drawn.empty())
            write_png(args.prefix + "-ids.png",
                      false_colour(drawn, scene.camera.width, scene.camera.height));
        std::printf("\nwrote %s-{ray,hybrid,diff%s}.png\n", args.prefix.c_str(),
                    drawn.empty() ? "" : ",ids");
    }
    if (!args.json.empty())
        write_file_atomically(args.json, comparison_json(args, c).dump(2) + "\n");
    return 0;
}

} // namespace

void CompareArgs::add_to(CLI::App& cmd) {
    scene.add_to(cmd);
    frame.add_to(cmd, false);
    cmd.add_option("-o,--output", prefix,
                   "Write PREFIX-ray.png, -hybrid.png, -diff.png and -ids.png; with --a/--b "
                   "PREFIX-a.png, -b.png, -heat.png and -causes.png (PREFIX.exr: also "
                   "PREFIX-heat.exr)");
    cmd.add_option("--json", json, "Also write the measurements as JSON here");
    a_option = cmd.add_option(
        "--a", a,
        "Side A's render flags, quoted (\"--max-depth 2 --accel grid\"), or exact (ray traced in "
        "double, depth 64, no cut-off); unset flags are compare's own (docs/DIFFERENCES.md)");
    b_option = cmd.add_option("--b", b, "Side B's render flags, as --a");
    cmd.add_flag("--exr", exr,
                 "With --a/--b: also write the float error |A - B| as PREFIX-heat.exr");
}

Command add_compare_command(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Render two settings side by side (hybrid and ray mode unless --a/--b say "
                   "otherwise), measure the difference and say why each pixel differs");
    args->add_to(*cmd);
    return {cmd, [args] { args->sides() ? check_compare_sides(*args) : (void)prepare(*args); },
            [args] { return guarded([&] { return run_compare(*args); }); }};
}

} // namespace glint
