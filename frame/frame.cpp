#include "frame/frame.h"

#include "trace/stopwatch.h"

#include <stdexcept>

namespace glint {

void draw_item_buffers(const World& world, const FrameSettings& settings, Frame& frame) {
    // Model only what the scene needs: ray mode and an empty scene get no GL context.
    if (settings.mode != Mode::hybrid || world.objects().empty()) return;
    // The GL pass runs before the tracing, not beside it: on 2 cores they would only compete.
    const auto context = timed(frame.times.context, [&] { return make_context(settings.gl); });
    frame.gl_renderer = context->renderer();
    ItemBuffer items = timed(frame.times.compile, [] { return ItemBuffer(); });
    timed(frame.times.upload, [&] {
        items.upload(world, settings.raster, settings.tessellation);
        return 0;
    });
    // Pixel centres where a pass takes them (N = 1, adaptive's first pass), and the N×N
    // sample grid where one is traced (antialiasing, trace/sampling.h).
    const RenderSettings& render = world.settings();
    if (render.samples == 1 || render.antialias == Antialias::adaptive)
        frame.items = timed(frame.times.raster, [&] { return items.draw(world); });
    // Adaptive without rule 3 traces its refined pixels' samples by ray: they are a few
    // percent of the N×N grid, which would cost N² item buffers to draw.
    const bool sample_grid =
        render.samples > 1 && (render.antialias == Antialias::uniform || settings.aa_sample_ids);
    if (sample_grid)
        frame.sample_items =
            timed(frame.times.raster, [&] { return items.draw(world, false, render.samples); });
    frame.deviations = items.deviations();
    frame.proxies = items.proxies(), frame.tessellated = items.tessellated();
    // The resolve's bins (trace/primary_hits.h) count as resolving: trace/ builds them.
    timed(frame.times.primary, [&] {
        if (frame.items) bin_objects(world, frame.items->ids);
        if (frame.sample_items) bin_objects(world, frame.sample_items->ids);
        return 0;
    });
}

PrimarySource primary_source(const Frame& frame, Resolve resolve) {
    PrimarySource source; // ray mode: every camera ray
    if (!frame.items && !frame.sample_items) return source;
    source.resolve = resolve;
    if (frame.items) source.ids = &frame.items->ids;
    if (frame.sample_items) source.sample_ids = &frame.sample_items->ids;
    return source;
}

Frame render_frame(const World& world, const FrameSettings& settings,
                   std::atomic<int>* tiles_done) {
    Frame frame;
    draw_item_buffers(world, settings, frame);
    frame.result = trace_frame(world, primary_source(frame, settings.resolve), frame.primary_stats,
                               {settings.threads, tiles_done, settings.exchange}, frame.times,
                               settings.aovs);
    return frame;
}

Frame render_frame(const Scene& scene, std::optional<AccelKind> accel,
                   const FrameSettings& settings, std::atomic<int>* tiles_done,
                   const std::shared_ptr<const SceneGeometry>& geometry) {
    if (settings.precision == Precision::f64) {
        if (settings.mode != Mode::ray)
            throw std::invalid_argument("double precision renders in ray mode only");
        Frame frame;
        frame.result =
            render_ray_frame(Precision::f64, scene, accel,
                             {settings.threads, tiles_done, settings.exchange}, frame.times);
        return frame;
    }
    double prepare = 0;
    const World world = timed(
        prepare, [&] { return geometry ? World(scene, geometry, accel) : World(scene, accel); });
    Frame frame = render_frame(world, settings, tiles_done);
    frame.times.prepare = prepare;
    return frame;
}

} // namespace glint
