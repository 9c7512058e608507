// Measuring one setting of `glint tradeoff`: its frames rendered side by side, and a run's figures
// as MPI ranks exchange them.
#include "app/tradeoff.h"

#include "frame/difference_maps.h"
#include "io/png.h"

#include <algorithm>

namespace glint {
namespace tradeoff {

namespace {

// Pixel replication up to width × height (nearest neighbour: what a preview shows).
FloatImage enlarge(const FloatImage& small, int width, int height) {
    if (small.empty() || (small.width == width && small.height == height)) return small;
    FloatImage out(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float* p =
                small.pixel(static_cast<std::size_t>(y * small.height / height) * small.width +
                            x * small.width / width);
            std::copy(p, p + 3, out.pixel(static_cast<std::size_t>(y) * width + x));
        }
    return out;
}

} // namespace

Side side_of(const Scene& scene, const Setting& s, const TradeoffArgs& args) {
    Side side;
    side.label = s.label(scene);
    side.scene = scene;
    side.scene.render = {s.max_depth, s.min_reflectivity, s.samples, s.antialias, s.aa_threshold};
    side.accel = s.accel;
    side.frame = s.frame;
    side.frame.gl = *from_name<GlBackend>(args.gl); // checked by --gl
    side.frame.threads = args.threads;
    side.resampled = s.divisor > 1;
    return side;
}

Run render_once(const Scene& scene, const Setting& s, const TradeoffArgs& args,
                const std::shared_ptr<const SceneGeometry>& geometry) {
    const Side side = side_of(scene, s, args);
    Scene copy = side.scene;
    copy.camera.width = std::max(1, scene.camera.width / s.divisor);
    copy.camera.height = std::max(1, scene.camera.height / s.divisor);
    Run run;
    run.setting = s;
    run.frame = render_frame(copy, s.accel, side.frame, nullptr, geometry);
    run.bound = cutoff_bound(copy, run.frame.result);
    RenderResult& result = run.frame.result;
    result.radiance = enlarge(result.radiance, scene.camera.width, scene.camera.height);
    result.clamped = enlarge(result.clamped, scene.camera.width, scene.camera.height);
    return run;
}

Run measure(const Scene& scene, const Setting& s, const TradeoffArgs& args,
            const std::shared_ptr<const SceneGeometry>& geometry) {
    std::vector<Run> runs;
    for (int i = 0; i < args.repeat; ++i) runs.push_back(render_once(scene, s, args, geometry));
    std::sort(runs.begin(), runs.end(),
              [](const Run& a, const Run& b) { return a.frame_seconds() < b.frame_seconds(); });
    return std::move(runs[runs.size() / 2]);
}

FrameDifference why_it_differs(const Scene& scene, const RenderedSide& reference, Run& run,
                               const TradeoffArgs& args,
                               const std::shared_ptr<const SceneGeometry>& geometry) {
    RenderedSide side(side_of(scene, run.setting, args), std::move(run.frame), geometry);
    FrameDifference d = difference(reference, side, false);
    run.frame = std::move(side).take_frame();
    return d;
}

CauseFigures cause_figures(const FrameDifference& d) {
    CauseFigures out;
    for (std::size_t c = 1; c < kCauses; ++c) {
        out.at(static_cast<Cause>(c)).pixels = d.tallies[c].pixels;
        out.at(static_cast<Cause>(c)).squared_error = d.tallies[c].squared_error;
    }
    return out;
}

void budget_thumbnails(SceneResult& sr, const RenderedSide& exact, const TradeoffArgs& args,
                       const std::shared_ptr<const SceneGeometry>& geometry, const fs::path& out) {
    constexpr int kThumbnailWidth = 240;
    const Image exact_bytes = exact.frame().result.bytes();
    for (const Budget& budget : error_budgets()) {
        const Run* best = fastest(sr.runs, budget.within);
        if (!best || best->diff.max_abs_error == 0 || !best->thumbnails.empty()) continue;
        Run& run = sr.runs[static_cast<std::size_t>(best - sr.runs.data())];
        // Measured on another rank: only its figures came here.
        Run again;
        Run& measured = run.frame.result.radiance.empty()
                            ? (again = render_once(sr.scene, run.setting, args, geometry), again)
                            : run;
        const FrameDifference d = why_it_differs(sr.scene, exact, measured, args, geometry);
        const MapThumbnails maps = map_thumbnails(d, exact_bytes, kThumbnailWidth);
        run.thumbnails = sr.name + "-" + budget.slug;
        write_png(out / (run.thumbnails + "-heat.png"), maps.heat);
        write_png(out / (run.thumbnails + "-causes.png"), maps.causes);
    }
}

RunFigures figures_of(const Run& r) {
    return {r.frame.times,
            r.frame.result.rays,
            r.diff,
            r.agreement,
            r.bound.max,
            r.bound.pixels_over_one,
            r.bound.largest_omitted_weight,
            r.bound_held,
            r.refined,
            r.pixels,
            r.causes};
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
    r.causes = f.causes;
    return r;
}

} // namespace tradeoff
} // namespace glint
