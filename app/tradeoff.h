// `glint tradeoff`'s parts (docs/TRADEOFF.md), a file each: the sweep of settings
// (tradeoff_sweep.cpp), measuring a setting's runs (tradeoff_measure.cpp), and the CSV, plots and
// summary (tradeoff_reports.cpp); tradeoff_command.cpp runs them in order.
#pragma once

#include "app/rank_records.h"
#include "frame/difference.h"
#include "frame/frame.h"
#include "trace/cutoff.h"
#include "trace/image_metrics.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint {
namespace tradeoff {

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

// A threshold as labels and the summary write it ("%g").
std::string format_threshold(float threshold);

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
    CauseFigures causes;                  // why its pixels differ from the reference's
    // The fastest run of an error budget: the stem of its heat and cause map thumbnails.
    std::string thumbnails;

    // Per frame (PhaseTimes::per_frame). Subtracting the GL set-up whole, hidden or not, once made
    // tree-3's frame take −0.0001 s, which gnuplot's log axis crashed on (a segmentation fault
    // in Cli.CompareAndTradeoffTakeNffAndObjScenes, 1 run in 13).
    double frame_seconds() const { return frame.times.per_frame(); }
    double total_seconds() const { return frame.times.total(); }
};

struct SceneResult {
    std::string name;
    fs::path path;
    Scene scene;
    std::vector<Run> runs;
    CutoffBound reference_bound;
    double reference_seconds = 0;
    double grid_seconds = 0; // the uniform 8×8 image the antialiasing knobs are measured against
};

// The sweep for one scene: each knob varied alone from the default setting (hybrid, auto raster,
// tessellation 32, exact, the scene's depth and cut-off, automatic structure, full size).
// The trace-only knobs (depth, cut-off, structure, size, precision) are swept in ray mode so
// that nothing else changes the image. Keyed by label: a setting reached by two knobs runs once.
std::vector<std::pair<std::string, Setting>> sweep(const Scene& scene, int samples);

// The scene as `s` renders it, at the scene's full size (a smaller run is enlarged to it).
Side side_of(const Scene& scene, const Setting& s, const TradeoffArgs& args);

// Why the run's pixels differ from its reference's (the exact image, or the uniform 8×8 one):
// its frame wrapped as a side of the comparison (frame/difference.h), then given back to it.
FrameDifference why_it_differs(const Scene& scene, const RenderedSide& reference, Run& run,
                               const TradeoffArgs& args,
                               const std::shared_ptr<const SceneGeometry>& geometry);

// The tallies a run keeps (and MPI ranks send): pixels and squared error per cause.
CauseFigures cause_figures(const FrameDifference& d);

// The heat and cause map thumbnails of each error budget's fastest run (against the exact image),
// written to `out` as <scene>-<budget>-heat.png and -causes.png and named in the run
// (Run::thumbnails). A run measured on another rank is rendered again for them.
void budget_thumbnails(SceneResult& sr, const RenderedSide& exact, const TradeoffArgs& args,
                       const std::shared_ptr<const SceneGeometry>& geometry, const fs::path& out);

// An error budget of the summary: its name and the runs within it.
struct Budget {
    std::string name; // "PSNR ≥ 40 dB"
    std::string slug; // for file names: "psnr-40"
    std::function<bool(const Run&)> within;
};
// The summary's error budgets, against the exact image.
std::vector<Budget> error_budgets();
// The fastest run within a budget, if any.
const Run* fastest(const std::vector<Run>& runs, const std::function<bool(const Run&)>& within);

// One render of `scene` with `s`; the images are deterministic, so only times differ per repeat.
// `geometry`: the scene's meshes and materials, prepared once for the whole sweep.
Run render_once(const Scene& scene, const Setting& s, const TradeoffArgs& args,
                const std::shared_ptr<const SceneGeometry>& geometry);

// `repeat` renders side by side; keeps the one with the median frame time.
Run measure(const Scene& scene, const Setting& s, const TradeoffArgs& args,
            const std::shared_ptr<const SceneGeometry>& geometry);

// A measured run's figures, for the rank that writes the CSV (MPI ranks spread a sweep):
// everything the CSV, the plots and the summary read but the image and the setting, which that
// rank knows already.
RunFigures figures_of(const Run& r);

// A run rebuilt from another rank's figures (no image, no setting: the caller sets it).
Run run_from_figures(const RunFigures& f);

// A PSNR as the reports write it: one decimal, or "exact".
std::string psnr_text(double psnr);

// Time against PSNR, a colour per knob, the Pareto front a line with its settings named; runs
// identical to the exact image are drawn on a dashed line above the largest finite PSNR.
void plot(const std::string& name, const std::vector<Run>& runs, const fs::path& dir,
          const std::string& reference);

// The CSV, a row per run of every scene (docs/TRADEOFF.md, "The CSV").
void write_csv(const std::vector<SceneResult>& results, const fs::path& path);

// The summary, one document written top to bottom in one body: its parts would each need the
// same five arguments, and the order of the document is the order of the code.
std::string markdown(const std::vector<SceneResult>& results, const TradeoffArgs& args,
                     const fs::path& plots, const std::string& gl_renderer, double seconds);

} // namespace tradeoff
} // namespace glint
