#include "frame/difference.h"

#include "io/error.h"

#include "trace/explain.h"
#include "trace/stopwatch.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace glint {

void make_exact(Side& side) {
    side.frame.mode = Mode::ray;
    side.frame.precision = Precision::f64;
    side.scene.render.max_depth = kMaxDepth;
    side.scene.render.min_reflectivity = 0;
}

std::string describe_side(const Side& side) {
    const FrameSettings& f = side.frame;
    const RenderSettings& r = side.scene.render;
    std::ostringstream out;
    out << name_of(f.mode);
    if (f.precision == Precision::f64) out << " double";
    if (f.mode == Mode::hybrid) {
        out << " " << name_of(f.raster);
        if (f.raster != RasterMode::proxy) out << " tess " << f.tessellation;
        out << " " << name_of(f.resolve);
    }
    out << ", depth " << r.max_depth << ", ";
    if (r.min_reflectivity > 0)
        out << "cut-off " << r.min_reflectivity;
    else
        out << "no cut-off";
    if (r.samples > 1) {
        out << ", " << r.samples << "x" << r.samples << " " << name_of(r.antialias);
        if (r.antialias == Antialias::adaptive) out << " " << r.aa_threshold;
    }
    if (side.accel) out << ", " << name_of(*side.accel);
    return out.str();
}

RenderedSide::RenderedSide(Side side) : side_(std::move(side)) {
    if (side_.frame.precision == Precision::f64) {
        frame_ = render_frame(side_.scene, side_.accel, side_.frame);
        tracer_ = f64::ray_pixel_tracer(side_.scene, side_.accel);
        return;
    }
    // As render_frame from a scene does, keeping the World for the pixels traced again.
    std::optional<GlPass> pass;
    if (needs_gl(side_.frame, side_.scene.objects.size())) pass.emplace(side_.frame);
    double prepare = 0;
    world_ =
        timed(prepare, [&] { return std::make_shared<const World>(side_.scene, side_.accel); });
    frame_ = render_frame(*world_, side_.frame, nullptr, pass ? &*pass : nullptr);
    frame_.times.prepare = prepare;
}

RenderedSide::RenderedSide(Side side, Frame frame,
                           const std::shared_ptr<const SceneGeometry>& geometry)
    : side_(std::move(side)), frame_(std::move(frame)) {
    if (side_.resampled) return; // no pixel of it is traced again
    if (side_.frame.precision == Precision::f64)
        tracer_ = f64::ray_pixel_tracer(side_.scene, side_.accel);
    else
        world_ = geometry ? std::make_shared<const World>(side_.scene, geometry, side_.accel)
                          : std::make_shared<const World>(side_.scene, side_.accel);
}

RenderedSide::RenderedSide(Side side, std::shared_ptr<const World> world,
                           std::shared_ptr<const IdImage> ids)
    : side_(std::move(side)), world_(std::move(world)),
      ids_(side_.frame.mode == Mode::hybrid ? std::move(ids) : nullptr) {
    const PrimarySource source{ids_.get(), side_.frame.resolve};
    frame_.result =
        trace_frame(*world_, source, frame_.primary_stats, {side_.frame.threads}, frame_.times);
}

RenderedSide::~RenderedSide() = default;
RenderedSide::RenderedSide(RenderedSide&&) noexcept = default;

std::vector<PixelTrees> RenderedSide::trees(std::span<const std::uint32_t> pixels,
                                            std::span<const int> depths) const {
    const std::vector<std::uint8_t>& refined = frame_.result.refined;
    if (pixels.empty()) return {};
    if (tracer_) return tracer_->trees(pixels, refined, depths);
    if (!world_) throw std::logic_error("a resampled frame's pixels are not traced again");
    const PrimarySource source = ids_ ? PrimarySource{ids_.get(), side_.frame.resolve}
                                      : primary_source(frame_, side_.frame.resolve);
    if (!depth_worlds_) depth_worlds_ = std::make_unique<DepthWorlds>(side_.scene, *world_);
    return many_pixel_trees(*depth_worlds_, source, pixels, refined, depths);
}

int RenderedSide::grid_at(std::uint32_t p) const {
    if (side_.resampled) return 0;
    const RenderSettings& render = side_.scene.render;
    const std::vector<std::uint8_t>& refined = frame_.result.refined;
    const bool grid = render.samples > 1 && (render.antialias == Antialias::uniform ||
                                             (!refined.empty() && refined[p] != 0));
    return grid ? render.samples : 1;
}

double FrameDifference::share(Cause cause) const {
    const CauseTally& t = tallies[static_cast<std::size_t>(cause)];
    if (squared_error > 0) return t.squared_error / squared_error;
    return differing > 0 ? static_cast<double>(t.pixels) / static_cast<double>(differing) : 0;
}

namespace {

bool radiance_differs(const float* a, const float* b) {
    return a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
}

// Adds a differing pixel to its cause's tally.
void count(FrameDifference& d, const Divergence& why, double squared, double largest) {
    CauseTally& t = d.tallies[static_cast<std::size_t>(why.cause)];
    ++t.pixels;
    t.squared_error += squared;
    t.largest = std::max(t.largest, largest);
    if (why.cause == Cause::depth || why.cause == Cause::cutoff || why.cause == Cause::secondary) {
        const auto level = static_cast<std::size_t>(why.level);
        if (t.levels.size() <= level) t.levels.resize(level + 1);
        ++t.levels[level];
    }
    ++d.differing;
    d.squared_error += squared;
}

} // namespace

FrameDifference difference(const RenderedSide& a, const RenderedSide& b, bool radiance) {
    const RenderResult &ra = a.frame().result, &rb = b.frame().result;
    FrameDifference d;
    d.width = ra.radiance.width, d.height = ra.radiance.height;
    const std::size_t pixels = static_cast<std::size_t>(d.width) * d.height;
    d.causes.assign(pixels, Cause::none);
    d.error.assign(pixels, 0.0f);
    const FloatImage &da = ra.display(), &db = rb.display();
    std::vector<std::uint32_t> differing;
    for (std::size_t p = 0; p < pixels; ++p) {
        const float *x = ra.radiance.pixel(p), *y = rb.radiance.pixel(p);
        float largest = 0;
        for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(x[k] - y[k]));
        d.error[p] = largest;
        d.largest = std::max(d.largest, static_cast<double>(largest));
        bool differs = radiance && radiance_differs(x, y);
        for (int k = 0; k < 3 && !differs; ++k)
            differs = to_byte(da.pixel(p)[k]) != to_byte(db.pixel(p)[k]);
        if (differs) differing.push_back(static_cast<std::uint32_t>(p));
    }
    // Where the grids differ the cause is sampling before any tree is walked; the rest are
    // traced again on both sides, in chunks (every differing pixel's trees at once took 14 GB on
    // glass.json at 800x600 against exact).
    constexpr std::size_t kChunk = 512;
    std::vector<Divergence> why(differing.size(), Divergence{Cause::sampling});
    std::vector<std::size_t> at; // each traced pixel's index in `differing`
    for (std::size_t i = 0; i < differing.size(); ++i)
        if (a.grid_at(differing[i]) == b.grid_at(differing[i])) at.push_back(i);
    const Stopwatch watch;
    std::vector<std::uint32_t> chunk;
    std::vector<int> depths;
    for (std::size_t first = 0; first < at.size(); first += kChunk) {
        const std::size_t end = std::min(at.size(), first + kChunk);
        chunk.clear();
        for (std::size_t k = first; k < end; ++k) chunk.push_back(differing[at[k]]);
        // The shallower side whole; the other traced only to one level below the first's deepest
        // node, D + 1. The walk finds the same there as on the whole trees: it visits nodes in
        // the order they are traced, and the first ray at D + 1 (cast before any deeper one, so
        // before the tree's ray budget can run out) is one the shallower tree lacks, so the walk
        // parts there at the latest; everything before it is traced the same either way. Glass
        // against exact (depth 64, no cut-off) traced whole took longer than the exact frame.
        const bool a_first = a.side().scene.render.max_depth <= b.side().scene.render.max_depth;
        const RenderedSide& shallow = a_first ? a : b;
        const RenderedSide& deep = a_first ? b : a;
        const std::vector<PixelTrees> ts = shallow.trees(chunk);
        depths.clear();
        for (const PixelTrees& t : ts) depths.push_back(deepest(t) + 1);
        const std::vector<PixelTrees> td = deep.trees(chunk, depths);
        for (std::size_t k = first; k < end; ++k)
            why[at[k]] = a_first ? first_divergence(ts[k - first], td[k - first])
                                 : first_divergence(td[k - first], ts[k - first]);
    }
    d.trace_seconds = watch.seconds();
    d.traced = at.size();
    for (std::size_t i = 0; i < differing.size(); ++i) {
        const std::uint32_t p = differing[i];
        d.causes[p] = why[i].cause;
        const float *x = ra.radiance.pixel(p), *y = rb.radiance.pixel(p);
        double squared = 0;
        for (int k = 0; k < 3; ++k) squared += double(x[k] - y[k]) * double(x[k] - y[k]);
        count(d, why[i], squared, d.error[p]);
    }
    return d;
}

Divergence pixel_difference(const PixelTrees& a, const PixelTrees& b, bool radiance) {
    bool differs = a.bytes != b.bytes;
    for (int k = 0; k < 3 && radiance && !differs; ++k)
        differs = static_cast<float>(a.radiance[k]) != static_cast<float>(b.radiance[k]);
    return differs ? first_divergence(a, b) : Divergence{};
}

} // namespace glint
