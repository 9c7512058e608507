// `glint tradeoff`: sweeps the knobs that trade speed for accuracy, one at a time from the
// default setting, timing each run side by side in one process and comparing its image with the
// exact one: ray traced in double precision, reflections followed as deep as glint allows with
// no weight cut-off. Writes a CSV (a row per run), a plot per scene of time against error with
// the Pareto front (gnuplot, SVG and PNG) and a markdown summary (docs/TRADEOFF.md).
#include "app/distributed.h"
#include "app/rank_records.h"
#include "app/options.h"

#include "io/error.h"
#include "io/write_file.h"
#include "trace/cutoff.h"
#include "trace/image_metrics.h"
#include "trace/stopwatch.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

struct TradeoffArgs {
    std::vector<std::string> scenes;
    std::string output = "out/tradeoff";
    std::string summary; // default: <output>/summary.md
    std::string size;
    std::string gl = "osmesa";
    int repeat = 3;
    int threads = 0;
    int samples = 4; // the adaptive sweep's grid, and the uniform sweep's largest

    fs::path summary_path() const {
        return summary.empty() ? fs::path(output) / "summary.md" : fs::path(summary);
    }
};

std::string format_threshold(float threshold) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(threshold));
    return text;
}

// The uniform grid the antialiasing knobs are measured against.
constexpr int kGridReference = 8;

// One point of the sweep: everything that may differ from the default setting. The frame's
// gl and threads come from the command line.
struct Setting {
    FrameSettings frame;
    int max_depth = 0;
    float min_reflectivity = 0;
    std::optional<AccelKind> accel; // nothing: list below kListBelow objects, else bvh
    int divisor = 1;                // rendered at 1/divisor of the size, then enlarged
    int samples = 1;                // antialiasing (trace/sampling.h)
    Antialias antialias = Antialias::uniform;
    float aa_threshold = kDefaultAaThreshold;
    // The antialiasing knobs' error is measured against the uniform 8×8 image of the same
    // setting, not the exact one-sample image: what sampling alone costs or gains.
    bool against_grid = false;

    // A short name for tables and plots, e.g. "hybrid mesh tess 8 trust".
    std::string label(const Scene& scene) const {
        const FrameSettings& f = frame;
        std::string s(name_of(f.mode));
        if (f.precision == Precision::f64) s.append(" ").append(name_of(f.precision));
        if (f.mode == Mode::hybrid) {
            s.append(" ").append(name_of(f.raster));
            if (f.raster != RasterMode::proxy) s += " tess " + std::to_string(f.tessellation);
            if (f.resolve == Resolve::trust) s.append(" ").append(name_of(f.resolve));
        }
        if (max_depth != scene.render.max_depth) s += " depth " + std::to_string(max_depth);
        if (min_reflectivity != scene.render.min_reflectivity) {
            char text[32];
            std::snprintf(text, sizeof text, " cut-off %g", static_cast<double>(min_reflectivity));
            s += text;
        }
        if (accel) s.append(" ").append(name_of(*accel));
        if (divisor > 1) s += " 1/" + std::to_string(divisor) + " size";
        if (samples > 1 || against_grid) { // 1x1 against the grid: not the exact-image run
            s += " " + std::to_string(samples) + "x" + std::to_string(samples);
            if (antialias == Antialias::adaptive)
                s += " adaptive " + format_threshold(aa_threshold);
        }
        return s;
    }
};

// The sweep for one scene: each knob varied alone from the default setting (hybrid, auto raster,
// tessellation 32, exact, the scene's depth and cut-off, automatic structure, full size).
// The trace-only knobs (depth, cut-off, structure, size, precision) are swept in ray mode so
// that nothing else changes the image. Keyed by label: a setting reached by two knobs runs once.
std::vector<std::pair<std::string, Setting>> sweep(const Scene& scene, int samples) {
    Setting hybrid;
    hybrid.max_depth = scene.render.max_depth;
    hybrid.min_reflectivity = scene.render.min_reflectivity;
    Setting ray = hybrid;
    ray.frame.mode = Mode::ray;
    std::vector<std::pair<std::string, Setting>> out;
    const auto add = [&](const char* knob, Setting s) { out.emplace_back(knob, s); };
    add("mode", hybrid);
    add("mode", ray);
    for (const Resolve resolve : {Resolve::exact, Resolve::trust}) {
        Setting s = hybrid;
        s.frame.resolve = resolve;
        for (const int tess : {4, 8, 16, 32, 64}) {
            s.frame.tessellation = tess;
            add(resolve == Resolve::exact ? "tessellation" : "resolve", s);
        }
        s.frame.tessellation = kDefaultTessellation;
        for (const RasterMode raster : {RasterMode::mesh, RasterMode::proxy}) {
            s.frame.raster = raster;
            add("raster", s);
        }
    }
    for (int depth = 0; depth <= 8; ++depth) {
        Setting s = ray;
        s.max_depth = depth;
        add("max_depth", s);
    }
    for (const float cutoff : {0.0f, 0.001f, 0.01f, 0.03f, 0.1f}) {
        Setting s = ray;
        s.min_reflectivity = cutoff;
        add("min_reflectivity", s);
    }
    for (const AccelKind kind : all_values<AccelKind>()) {
        Setting s = ray;
        s.accel = kind;
        add("accel", s);
    }
    for (const int divisor : {2, 4}) {
        Setting s = ray;
        s.divisor = divisor;
        add("resolution", s);
    }
    Setting precise = ray;
    precise.frame.precision = Precision::f64;
    add("precision", precise);
    // The exact image's own setting in float: what double precision alone adds.
    Setting untruncated = ray;
    untruncated.max_depth = kMaxDepth;
    untruncated.min_reflectivity = 0;
    add("precision", untruncated);
    // Antialiasing, in the default (hybrid) mode, against the uniform 8×8 image: uniform grids
    // up to --samples, then adaptive at that grid over the threshold.
    Setting grid = hybrid;
    grid.against_grid = true;
    for (int n = 1; n <= samples; ++n) {
        grid.samples = n;
        add("samples", grid);
    }
    grid.samples = samples;
    grid.antialias = Antialias::adaptive;
    for (const float threshold : {0.005f, 0.01f, 0.02f, 0.05f, 0.1f}) {
        grid.aa_threshold = threshold;
        add("aa_threshold", grid);
    }
    return out;
}

struct Run {
    std::string knobs; // every sweep that reached this setting, '+'-joined
    std::string label;
    Setting setting;
    Frame frame; // its image enlarged to full size
    CutoffBound bound;
    std::optional<bool> bound_held; // float ray runs at full size: checked pixel by pixel
    ImageDifference diff{};
    std::optional<double> agreement;      // against the reference's ids; not for enlarged runs
    std::optional<std::uint64_t> refined; // adaptive antialiasing: pixels that took the grid
    std::uint64_t pixels = 0;             // of the image rendered

    // Per frame: the frame's wall time less what the one-time GL set-up (context, shader
    // compilation) added to it. The set-up runs first on the GL pass's thread, beside the World's
    // preparation, and `overlapped` counts the seconds of that pass the preparation hid: those
    // came off the wall time already. Subtracting the set-up whole again made a frame whose
    // set-up was hidden take negative time (−0.0001 s for tree-3), which gnuplot's log axis
    // crashed on (a segmentation fault in Cli.CompareAndTradeoffTakeNffAndObjScenes, 1 run in 13).
    double frame_seconds() const {
        const PhaseTimes& t = frame.times;
        return t.total() - std::max(0.0, t.context + t.compile - t.overlapped);
    }
    double total_seconds() const { return frame.times.total(); }
};

// Pixel replication up to width × height (nearest neighbour: what a preview shows).
FloatImage enlarge(const FloatImage& small, int width, int height) {
    if (small.empty() || (small.width == width && small.height == height)) return small;
    FloatImage out(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float* p = small.pixel(static_cast<std::size_t>(y * small.height / height) *
                                             small.width +
                                         x * small.width / width);
            std::copy(p, p + 3, out.pixel(static_cast<std::size_t>(y) * width + x));
        }
    return out;
}

// One render of `scene` with `s`; the images are deterministic, so only times differ per repeat.
// `geometry`: the scene's meshes and materials, prepared once for the whole sweep.
Run render_once(const Scene& scene, const Setting& s, const TradeoffArgs& args,
                const std::shared_ptr<const SceneGeometry>& geometry) {
    Scene copy = scene;
    copy.render = {s.max_depth, s.min_reflectivity, s.samples, s.antialias, s.aa_threshold};
    copy.camera.width = std::max(1, scene.camera.width / s.divisor);
    copy.camera.height = std::max(1, scene.camera.height / s.divisor);
    Run run;
    run.setting = s;
    FrameSettings settings = s.frame;
    settings.gl = *from_name<GlBackend>(args.gl); // checked by --gl
    settings.threads = args.threads;
    run.frame = render_frame(copy, s.accel, settings, nullptr, geometry);
    run.bound = cutoff_bound(copy, run.frame.result);
    RenderResult& result = run.frame.result;
    result.radiance = enlarge(result.radiance, scene.camera.width, scene.camera.height);
    result.clamped = enlarge(result.clamped, scene.camera.width, scene.camera.height);
    return run;
}

// `repeat` renders side by side; keeps the one with the median frame time.
Run measure(const Scene& scene, const Setting& s, const TradeoffArgs& args,
            const std::shared_ptr<const SceneGeometry>& geometry) {
    std::vector<Run> runs;
    for (int i = 0; i < args.repeat; ++i) runs.push_back(render_once(scene, s, args, geometry));
    std::sort(runs.begin(), runs.end(),
              [](const Run& a, const Run& b) { return a.frame_seconds() < b.frame_seconds(); });
    return std::move(runs[runs.size() / 2]);
}

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

std::string psnr_text(double psnr) {
    return std::isinf(psnr) ? "exact" : format("%.1f", psnr);
}

// Indices of the runs on the Pareto front of (frame time, PSNR): none is both faster and closer.
// Runs measured against different references (the exact image, the 8×8 grid) each have their own.
std::vector<std::size_t> pareto_front(const std::vector<Run>& runs) {
    std::vector<std::size_t> order(runs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return runs[a].frame_seconds() < runs[b].frame_seconds();
    });
    std::vector<std::size_t> front;
    for (const bool against_grid : {false, true}) {
        double best = -1;
        for (const std::size_t i : order)
            if (runs[i].setting.against_grid == against_grid && runs[i].diff.psnr_db > best)
                front.push_back(i), best = runs[i].diff.psnr_db;
    }
    return front;
}

// Runs gnuplot on `script`; throws when it fails.
void gnuplot(const std::string& script) {
    FILE* pipe = popen("gnuplot", "w");
    if (!pipe) throw std::runtime_error("cannot run gnuplot");
    std::fwrite(script.data(), 1, script.size(), pipe);
    if (pclose(pipe) != 0) throw std::runtime_error("gnuplot failed on the plot script");
}

// Time against PSNR, a colour per knob, the Pareto front a line with its settings named; runs
// identical to the exact image are drawn on a dashed line above the largest finite PSNR.
void plot(const std::string& name, const std::vector<Run>& runs, const fs::path& dir,
          const std::string& reference) {
    double top = 0;
    bool any_exact = false;
    for (const Run& r : runs) {
        if (std::isinf(r.diff.psnr_db))
            any_exact = true;
        else
            top = std::max(top, r.diff.psnr_db);
    }
    top += 10;
    const auto point = [&](const Run& r) {
        return std::to_string(r.frame_seconds()) + ' ' +
               std::to_string(std::isinf(r.diff.psnr_db) ? top : r.diff.psnr_db) + " \"" + r.label +
               "\"\n";
    };
    std::vector<std::string> knobs; // in sweep order, by the first knob that reached a run
    std::map<std::string, std::string> points;
    for (const Run& r : runs) {
        const std::string knob = r.knobs.substr(0, r.knobs.find('+'));
        if (!points.count(knob)) knobs.push_back(knob);
        points[knob] += point(r);
    }
    std::ostringstream script, draw;
    for (std::size_t k = 0; k < knobs.size(); ++k)
        script << "$knob" << k << " << EOD\n" << points[knobs[k]] << "EOD\n";
    script << "$front << EOD\n";
    for (const std::size_t i : pareto_front(runs)) script << point(runs[i]);
    script << "EOD\nset logscale x\nset grid\nset key outside right top\n"
           << "set xlabel 'frame time (s, log scale; GL context and shader compilation excluded)'\n"
           << "set ylabel 'PSNR against " << reference << " (dB)'\n"
           << "set title '" << name << ": time against error"
           << (any_exact ? " (dashed line: identical to " + reference + ")" : "") << "'\n";
    if (any_exact)
        script << "set arrow from graph 0, first " << top << " to graph 1, first " << top
               << " nohead dashtype 2\n";
    draw << "plot ";
    for (std::size_t k = 0; k < knobs.size(); ++k)
        draw << "$knob" << k << " using 1:2 with points pointtype 7 pointsize 1 title '" << knobs[k]
             << "', ";
    draw << "$front using 1:2 with steps linewidth 2 linecolor 'gray40' title 'Pareto front', "
            "$front using 1:2:3 with labels font ',8' offset 0.5,0.5 left notitle\n";
    const std::string base = (dir / name).string();
    gnuplot(script.str() +
            "set terminal svg size 1100,650 dynamic noenhanced font 'sans,11'\nset output '" +
            base + ".svg'\n" + draw.str());
    gnuplot(script.str() +
            "set terminal pngcairo size 1100,650 noenhanced font 'sans,10'\nset output '" + base +
            ".png'\n" + draw.str());
}

// The fastest run within an error budget, if any.
const Run* fastest(const std::vector<Run>& runs, const std::function<bool(const Run&)>& within) {
    const Run* best = nullptr;
    for (const Run& r : runs)
        if (within(r) && (!best || r.frame_seconds() < best->frame_seconds())) best = &r;
    return best;
}

struct SceneResult {
    std::string name;
    fs::path path;
    Scene scene;
    std::vector<Run> runs;
    CutoffBound reference_bound;
    double reference_seconds = 0;
    double grid_seconds = 0; // the uniform 8×8 image the antialiasing knobs are measured against
};

void write_csv(const std::vector<SceneResult>& results, const fs::path& path) {
    std::ostringstream csv;
    csv << "scene,width,height,knobs,label,precision,mode,raster,tessellation,resolve,max_depth,"
           "min_reflectivity,accel,divisor,seconds_frame,seconds_total,seconds_prepare,"
           "seconds_context,seconds_compile,seconds_upload,seconds_raster,seconds_primary,"
           "seconds_shading,psnr_db,max_abs_error_255,fraction_over_1_255,id_agreement,"
           "rays_primary,rays_shadow,rays_reflection,rays_transmission,cutoff_bound_255,cutoff_"
           "bound_held,pareto,samples,antialias,aa_threshold,refined_pixels,reference,"
           "fraction_over_2_255,rmse_radiance,max_error_radiance\n";
    for (const SceneResult& sr : results) {
        const std::vector<std::size_t> front = pareto_front(sr.runs);
        for (std::size_t i = 0; i < sr.runs.size(); ++i) {
            const Run& r = sr.runs[i];
            const Setting& s = r.setting;
            const FrameSettings& f = s.frame;
            const PhaseTimes& t = r.frame.times;
            const RayCounts& rays = r.frame.result.rays;
            const bool hybrid = f.mode == Mode::hybrid;
            csv << sr.name << ',' << sr.scene.camera.width << ',' << sr.scene.camera.height << ','
                << r.knobs << ",\"" << r.label << "\"," << name_of(f.precision) << ','
                << name_of(f.mode) << ',' << (hybrid ? name_of(f.raster) : "") << ','
                << (hybrid && f.raster != RasterMode::proxy ? std::to_string(f.tessellation) : "")
                << ',' << (hybrid ? name_of(f.resolve) : "") << ',' << s.max_depth << ','
                << s.min_reflectivity << ',' << (s.accel ? name_of(*s.accel) : "auto") << ','
                << s.divisor << ',' << r.frame_seconds() << ',' << r.total_seconds() << ','
                << t.prepare << ',' << t.context << ',' << t.compile << ',' << t.upload << ','
                << t.raster << ',' << t.primary << ',' << t.shading << ','
                << (std::isinf(r.diff.psnr_db) ? "inf" : format("%.3f", r.diff.psnr_db)) << ','
                << r.diff.max_abs_error << ',' << r.diff.fraction_over_one << ','
                << (r.agreement ? format("%.6f", *r.agreement) : "") << ',' << rays.primary << ','
                << rays.shadow << ',' << rays.reflection << ',' << rays.transmission << ','
                << r.bound.max << ',' << (r.bound_held ? (*r.bound_held ? "yes" : "no") : "") << ','
                << (std::find(front.begin(), front.end(), i) != front.end() ? "yes" : "") << ','
                << s.samples << ',' << name_of(s.antialias) << ',' << s.aa_threshold << ','
                << r.refined.value_or(0) << ',' << (s.against_grid ? "uniform 8x8" : "exact")
                << ',' << r.diff.fraction_over_two << ',' << format("%.6g", r.diff.rmse) << ','
                << format("%.6g", r.diff.max_radiance_error) << '\n';
        }
    }
    write_file_atomically(path, csv.str());
}

// The summary, one document written top to bottom in one body: its parts would each need the
// same five arguments, and the order of the document is the order of the code.
std::string markdown(const std::vector<SceneResult>& results, const TradeoffArgs& args,
                     const fs::path& plots, const std::string& gl_renderer, double seconds) {
    std::ostringstream md;
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    const int threads = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    md << "# Speed against accuracy\n\n"
       << "Generated by `glint tradeoff` on " << date << " (" << threads
       << " threads, GL: " << gl_renderer << ", median of " << args.repeat << " runs each, "
       << format("%.0f", seconds) << " s in all). Regenerate the shipped scenes' results with\n\n"
       << "```sh\n./glint tradeoff -o docs/tradeoff --summary docs/TRADEOFF.md\n```\n\n"
       << "**Exact image**: ray traced in double precision (`glint::f64`), reflections followed "
          "to depth "
       << kMaxDepth
       << " with no weight cut-off. **Error**: PSNR over every 8-bit channel (identical images: "
          "*exact*), largest channel difference, pixels off by more than 1/255; the CSV adds "
          "pixels off by more than 2/255 and, in linear radiance against the exact float image "
          "(errors below 1/255 and above 1 that bytes hide), the RMSE and the largest "
          "difference. **Frame time**: "
          "everything but the one-time set-up (GL context and shader compilation, ~0.2 s on "
          "llvmpipe, reported in the CSV; the meshes and their BVHs, prepared once per scene): "
          "preparing the world (transforms, the top-level acceleration structure), tessellation "
          "upload, item buffer, primary visibility, shading. Each knob "
          "is varied alone from the default setting (hybrid, mesh, tessellation 32, exact "
          "resolve, the scene's depth and cut-off, automatic structure, one sample a pixel: the "
          "antialiasing knobs have their own section per scene); the trace-only knobs in "
          "ray mode. Smaller sizes are enlarged by pixel replication before comparing. "
          "**Cut-off bound**: what the reflection cut-off may cost each pixel "
          "(`trace/cutoff.h`), checked on every pixel against the untruncated float render "
          "(*held*). All runs: [tradeoff.csv]("
       << (plots / "tradeoff.csv").generic_string() << ").\n\n";
    for (const SceneResult& sr : results) {
        md << "## " << sr.name << " (" << sr.scene.camera.width << "×" << sr.scene.camera.height
           << ", " << sr.scene.objects.size() << " objects)\n\n"
           << "![" << sr.name << ": frame time against PSNR]("
           << (plots / (sr.name + ".svg")).generic_string() << ")\n\n"
           << "The exact image took " << format("%.3f", sr.reference_seconds)
           << " s; its own cut-off bound is " << sr.reference_bound.max << "/255.\n\n"
           << "| error budget | fastest setting | frame time (s) | PSNR (dB) | max error |\n"
           << "|---|---|---:|---:|---:|\n";
        // Against the exact image: the antialiasing runs have their own table below.
        const auto exact = [](const Run& r) { return !r.setting.against_grid; };
        const std::vector<std::pair<std::string, std::function<bool(const Run&)>>> budgets = {
            {"PSNR ≥ 40 dB", [&](const Run& r) { return exact(r) && r.diff.psnr_db >= 40; }},
            {"PSNR ≥ 50 dB", [&](const Run& r) { return exact(r) && r.diff.psnr_db >= 50; }},
            {"every pixel within 1/255",
             [&](const Run& r) { return exact(r) && r.diff.max_abs_error <= 1; }},
            {"exact", [&](const Run& r) { return exact(r) && r.diff.max_abs_error == 0; }}};
        for (const auto& [budget, within] : budgets) {
            const Run* r = fastest(sr.runs, within);
            if (!r)
                md << "| " << budget << " | none of the runs | | | |\n";
            else
                md << "| " << budget << " | " << r->label << " | "
                   << format("%.4f", r->frame_seconds()) << " | " << psnr_text(r->diff.psnr_db)
                   << " | " << r->diff.max_abs_error << "/255 |\n";
        }
        md << "\n### Antialiasing\n\n"
           << "Against the uniform " << kGridReference << "×" << kGridReference
           << " image of the default setting (ray traced, " << format("%.3f", sr.grid_seconds)
           << " s): uniform grids, and adaptive at " << args.samples << "×" << args.samples
           << " over its threshold (docs/ANTIALIASING.md).\n\n"
           << "![" << sr.name << ": antialiasing, frame time against PSNR]("
           << (plots / (sr.name + "-antialiasing.svg")).generic_string() << ")\n\n"
           << "| setting | frame time (s) | PSNR (dB) | pixels within 2/255 | refined pixels |\n"
           << "|---|---:|---:|---:|---:|\n";
        for (const Run& r : sr.runs) {
            if (!r.setting.against_grid) continue;
            md << "| " << r.label << " | " << format("%.4f", r.frame_seconds()) << " | "
               << psnr_text(r.diff.psnr_db) << " | "
               << format("%.2f%%", 100 * (1 - r.diff.fraction_over_two)) << " | "
               << (r.refined ? format("%.1f%%", 100.0 * static_cast<double>(*r.refined) /
                                                    static_cast<double>(r.pixels))
                             : std::string("–"))
               << " |\n";
        }
        md << "\n<details><summary>Every run</summary>\n\n"
           << "| knob | setting | frame time (s) | PSNR (dB) | max error | off > 1/255 | id "
              "agreement | reflection rays | cut-off bound |\n"
           << "|---|---|---:|---:|---:|---:|---:|---:|---|\n";
        for (const Run& r : sr.runs)
            md << "| " << r.knobs << " | " << r.label << " | " << format("%.4f", r.frame_seconds())
               << " | " << psnr_text(r.diff.psnr_db) << " | " << r.diff.max_abs_error << " | "
               << format("%.3f%%", 100 * r.diff.fraction_over_one) << " | "
               << (r.agreement ? format("%.4f", *r.agreement) : "–") << " | "
               << r.frame.result.rays.reflection << " | " << r.bound.max << "/255"
               << (r.bound_held ? (*r.bound_held ? ", held" : ", **violated**") : "") << " |\n";
        md << "\n</details>\n\n";
    }
    return md.str();
}

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
        SceneResult sr{path.stem().string(), path, load_scene_with_notes(path, model), {}, {}, 0, 0};
        // The exact image, its float twin and the run being measured are alive together, and
        // the antialiasing runs draw an item buffer of --samples² samples a pixel.
        Scene sampled = sr.scene;
        sampled.render.samples = args.samples;
        check_frame_memory(sampled, Mode::hybrid, 3);
        results.push_back(std::move(sr));
    }
    return results;
}

// A measured run's figures, for the rank that writes the CSV (MPI ranks spread a sweep):
// everything the CSV, the plots and the summary read but the image and the setting, which that
// rank knows already.
RunFigures figures_of(const Run& r) {
    return {r.frame.times,           r.frame.result.rays,
            r.diff,                  r.agreement,
            r.bound.max,             r.bound.pixels_over_one,
            r.bound.largest_omitted_weight, r.bound_held,
            r.refined,               r.pixels};
}

Run run_from_figures(const RunFigures& f) {
    Run r;
    r.frame.times = f.times;
    r.frame.result.rays = f.rays;
    r.diff = f.diff;
    r.agreement = f.agreement;
    r.bound.max = f.bound_max, r.bound.pixels_over_one = f.bound_pixels_over_one;
    r.bound.largest_omitted_weight = f.largest_omitted_weight;
    r.bound_held = f.bound_held;
    r.refined = f.refined;
    r.pixels = f.pixels;
    return r;
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
        const Frame reference = render_frame(deep, std::nullopt, deep_ray);
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
        const Run grid = render_once(scene, grid_setting, args, geometry);
        sr.grid_seconds = grid.total_seconds();

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
            run.diff = compare_results(
                setting.against_grid ? grid.frame.result : reference.result, result);
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
