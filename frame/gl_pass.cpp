#include "frame/gl_pass.h"

#include "trace/stopwatch.h"

#include <algorithm>

namespace glint {

bool needs_gl(const FrameSettings& settings, std::size_t objects) {
    return settings.mode == Mode::hybrid && objects > 0;
}

GlPass::GlPass(const FrameSettings& settings)
    : settings_(settings), world_given_(world_.get_future()), done_seen_(done_.get_future()),
      thread_([this] { run(); }) {}

GlPass::~GlPass() {
    if (!handed_) world_.set_value(nullptr);
    thread_.join();
}

void GlPass::draw(const World& world) {
    handed_ = true;
    world_.set_value(&world);
}

void GlPass::finish(Frame& frame) {
    if (!handed_) throw std::logic_error("GlPass::finish before draw");
    const Stopwatch watch;
    done_seen_.get(); // rethrows the thread's exception
    const double waited = watch.seconds();
    frame.items = std::move(made_.items);
    frame.sample_items = std::move(made_.sample_items);
    frame.deviations = std::move(made_.deviations);
    frame.proxies = made_.proxies, frame.tessellated = made_.tessellated;
    frame.gl_renderer = std::move(made_.gl_renderer);
    PhaseTimes& t = frame.times;
    t.context = made_.times.context, t.compile = made_.times.compile;
    t.upload = made_.times.upload, t.raster = made_.times.raster;
    t.primary += made_.times.primary;
    const double pass = made_.times.context + made_.times.compile + made_.times.upload +
                        made_.times.raster + made_.times.primary;
    t.overlapped = std::max(0.0, pass - waited);
}

void GlPass::run() {
    // The context and the item buffer's GL objects are destroyed when this scope ends: on this
    // thread, after done_ is set, beside the caller's tracing.
    std::unique_ptr<GlContext> context;
    std::optional<ItemBuffer> items;
    try {
        Frame& frame = made_;
        context = timed(frame.times.context, [&] { return make_context(settings_.gl); });
        frame.gl_renderer = context->renderer();
        timed(frame.times.compile, [&] { return &items.emplace(); });
        const World* world = world_given_.get();
        if (!world) return;
        timed(frame.times.upload, [&] {
            items->upload(*world, settings_.raster, settings_.tessellation);
            return 0;
        });
        // Pixel centres where a pass takes them (N = 1, adaptive's first pass), and the N×N
        // sample grid where one is traced (antialiasing, trace/sampling.h).
        const RenderSettings& render = world->settings();
        if (render.samples == 1 || render.antialias == Antialias::adaptive)
            frame.items = timed(frame.times.raster, [&] { return items->draw(*world); });
        // Adaptive without rule 3 traces its refined pixels' samples by ray: they are a few
        // percent of the N×N grid, which would cost N² item buffers to draw.
        const bool sample_grid = render.samples > 1 && (render.antialias == Antialias::uniform ||
                                                        settings_.aa_sample_ids);
        if (sample_grid)
            frame.sample_items = timed(frame.times.raster,
                                       [&] { return items->draw(*world, false, render.samples); });
        frame.deviations = items->deviations();
        frame.proxies = items->proxies(), frame.tessellated = items->tessellated();
        // The resolve's bins (trace/primary_hits.h) count as resolving: trace/ builds them.
        timed(frame.times.primary, [&] {
            if (frame.items) bin_objects(*world, frame.items->ids);
            if (frame.sample_items) bin_objects(*world, frame.sample_items->ids);
            return 0;
        });
        done_.set_value();
    } catch (...) {
        done_.set_exception(std::current_exception());
        // A pass whose World is still to come is waited for by nobody: it ends here.
    }
}

} // namespace glint
