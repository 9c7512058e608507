// Measuring one setting of `glint tradeoff`: its frames rendered side by side, and a run's figures
// as MPI ranks exchange them.
#include "app/tradeoff.h"

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
            const float* p = small.pixel(static_cast<std::size_t>(y * small.height / height) *
                                             small.width +
                                         x * small.width / width);
            std::copy(p, p + 3, out.pixel(static_cast<std::size_t>(y) * width + x));
        }
    return out;
}

} // namespace

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

Run measure(const Scene& scene, const Setting& s, const TradeoffArgs& args,
            const std::shared_ptr<const SceneGeometry>& geometry) {
    std::vector<Run> runs;
    for (int i = 0; i < args.repeat; ++i) runs.push_back(render_once(scene, s, args, geometry));
    std::sort(runs.begin(), runs.end(),
              [](const Run& a, const Run& b) { return a.frame_seconds() < b.frame_seconds(); });
    return std::move(runs[runs.size() / 2]);
}

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

} // namespace tradeoff
} // namespace glint
