#include "frame/gl_pass.h"

#include "trace/stopwatch.h"

#include <algorithm>

namespace glint {

bool needs_gl(const FrameSettings& settings, std::size_t objects) {
    return settings.mode == Mode::hybrid && objects > 0;
}

GlPass::GlPass(const FrameSettings& settings)
    : settings_(settings), thread_([this] { run(); }) {}

GlPass::~GlPass() {
    {
        const std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void GlPass::draw(const World& world) {
    {
        const std::lock_guard lock(mutex_);
        if (handed_ && !done_) throw std::logic_error("GlPass::draw before the last finish");
        handed_ = true, done_ = false;
        world_ = &world;
    }
    changed_.notify_all();
}

void GlPass::finish(Frame& frame) {
    if (!handed_) throw std::logic_error("GlPass::finish before draw");
    const Stopwatch watch;
    {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return done_; });
        handed_ = false;
        if (error_) std::rethrow_exception(error_);
    }
    const double waited = watch.seconds();
    frame.items = std::move(made_.items);
    frame.sample_items = std::move(made_.sample_items);
    frame.deviations = std::move(made_.deviations);
    frame.proxies = made_.proxies, frame.tessellated = made_.tessellated;
    frame.gl_renderer = made_.gl_renderer;
    PhaseTimes& t = frame.times;
    t.context = made_.times.context, t.compile = made_.times.compile;
    t.upload = made_.times.upload, t.raster = made_.times.raster;
    t.primary += made_.times.primary;
    const double pass = made_.times.context + made_.times.compile + made_.times.upload +
                        made_.times.raster + made_.times.primary;
    t.overlapped = std::max(0.0, pass - waited);
    // The next frame reuses the context and shaders: they cost it nothing.
    made_.times = {};
}

void GlPass::draw_frame(const World& world, ItemBuffer& items) {
    Frame& frame = made_;
    timed(frame.times.upload, [&] {
        items.upload(world, settings_.raster, settings_.tessellation);
        return 0;
    });
    // Pixel centres where a pass takes them (N = 1, adaptive's first pass), and the N×N
    // sample grid where one is traced (antialiasing, trace/sampling.h).
    const RenderSettings& render = world.settings();
    if (render.samples == 1 || render.antialias == Antialias::adaptive)
        frame.items = timed(frame.times.raster, [&] { return items.draw(world); });
    // Adaptive without rule 3 traces its refined pixels' samples by ray: they are a few
    // percent of the N×N grid, which would cost N² item buffers to draw.
    const bool sample_grid = render.samples > 1 && (render.antialias == Antialias::uniform ||
                                                    settings_.aa_sample_ids);
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

void GlPass::run() {
    // The context and the item buffer's GL objects are destroyed when this scope ends: on this
    // thread, after the last frame is done, beside the caller's tracing.
    std::unique_ptr<GlContext> context;
    std::optional<ItemBuffer> items;
    const auto next_world = [&]() -> const World* {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return world_ || stopping_; });
        const World* world = world_;
        world_ = nullptr;
        return world;
    };
    const auto report = [&](std::exception_ptr error) {
        {
            const std::lock_guard lock(mutex_);
            done_ = true;
            error_ = error;
        }
        changed_.notify_all();
    };
    try {
        context = timed(made_.times.context, [&] { return make_context(settings_.gl); });
        made_.gl_renderer = context->renderer();
        timed(made_.times.compile, [&] { return &items.emplace(); });
    } catch (...) {
        // A pass that fails to start fails its first frame; one never handed a World ends here.
        if (next_world()) report(std::current_exception());
        return;
    }
    while (const World* world = next_world()) {
        try {
            draw_frame(*world, *items);
            report(nullptr);
        } catch (...) {
            report(std::current_exception());
            return;
        }
    }
}

} // namespace glint
