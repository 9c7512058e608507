#include "frame/frame.h"

#include "trace/stopwatch.h"

#include <stdexcept>

namespace glint {

void draw_item_buffers(const World& world, const FrameSettings& settings, Frame& frame) {
    // Model only what the scene needs: ray mode and an empty scene get no GL context.
    if (!needs_gl(settings, world.objects().size())) return;
    GlPass pass(settings);
    pass.draw(world);
    pass.finish(frame);
}

PrimarySource primary_source(const Frame& frame, Resolve resolve) {
    PrimarySource source; // ray mode: every camera ray
    if (!frame.items && !frame.sample_items) return source;
    source.resolve = resolve;
    if (frame.items) source.ids = &frame.items->ids;
    if (frame.sample_items) source.sample_ids = &frame.sample_items->ids;
    return source;
}

Frame render_frame(const World& world, const FrameSettings& settings, std::atomic<int>* tiles_done,
                   GlPass* pass) {
    Frame frame;
    if (pass) {
        pass->draw(world);
        pass->finish(frame);
    } else {
        draw_item_buffers(world, settings, frame);
    }
    FrameRequest request;
    // The ranks' tiles carry their ids and floats to rank 0 (the exchange's pixel records),
    // whoever asked.
    request.aovs = settings.aovs, request.ids = settings.ids || settings.exchange;
    request.radiance = settings.radiance || settings.exchange;
    frame.result = trace_frame(world, primary_source(frame, settings.resolve), frame.primary_stats,
                               settings.progress(tiles_done), frame.times, request);
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
                             settings.progress(tiles_done), frame.times);
        return frame;
    }
    // The GL pass starts first and makes its context and shaders while the World is built.
    std::optional<GlPass> pass;
    if (needs_gl(settings, scene.objects.size())) pass.emplace(settings);
    double prepare = 0;
    const World world = timed(
        prepare, [&] { return geometry ? World(scene, geometry, accel) : World(scene, accel); });
    Frame frame = render_frame(world, settings, tiles_done, pass ? &*pass : nullptr);
    frame.times.prepare = prepare;
    return frame;
}

} // namespace glint
