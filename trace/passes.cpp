#include "trace/passes.h"

#include "trace/sampling.h"
#include "trace/stopwatch.h"

#include <mutex>

namespace glint {
inline namespace GLINT_PRECISION {

bool ThreadSchedule::run(FramePass pass, const RenderResult& result, const TileWork& work) {
    TileProgress progress = progress_;
    // Spreading's rounds are not counted: how far it spreads is not known beforehand.
    if (pass == FramePass::spread) progress.tiles_done = nullptr;
    for_each_tile(result.width(), result.height(), progress, [&](int x0, int y0, int x1, int y1) {
        work({x0, y0, x1, y1});
    });
    return !progress.cancelled();
}

void ThreadSchedule::finish(FramePass, RenderResult&) {
    if (progress_.exchange) progress_.exchange->close();
}

int progress_steps(const RenderSettings& settings, int width, int height) {
    const bool adaptive = settings.samples > 1 && settings.antialias == Antialias::adaptive;
    return (adaptive ? 2 : 1) * tile_count(width, height);
}

namespace {

// What one tile of a pass did: its rays and resolve figures, and the seconds its primary hits
// and its shading took.
struct TileFigures {
    RayCounts rays;
    PrimaryStats stats;
    double primary = 0, shading = 0;
};

// The centres pass on one tile: its primary hits and their camera rays, kept for the tile alone
// in the thread's tile buffers (a frame's worth would cost a whole image of first-touched pages
// before the pass), then its pixels shaded.
TileFigures centres_tile(const World& world, const PrimarySource& source, const TileRect& r,
                         RenderResult& result, std::vector<std::uint64_t>* keys,
                         CentreObserver* observer) {
    TileFigures figures;
    Stopwatch watch;
    const std::size_t stride = static_cast<std::size_t>(r.x1 - r.x0);
    TileBuffers& buffers = tile_buffers();
    std::vector<Hit>& primary = buffers.primary;
    std::vector<Ray>& rays = buffers.primary_rays;
    primary.resize(r.pixels()), rays.resize(r.pixels()); // each one written by tile_primary_hits
    tile_primary_hits(world, source, r, primary.data(), stride, figures.stats, rays.data());
    figures.primary = watch.lap();
    figures.rays =
        shade_tile(world, primary.data(), stride, r, result, keys, observer, rays.data());
    figures.shading = watch.lap();
    return figures;
}

// The primary hits of the tile's pixel centres (§2's ray, whatever the grid) into result.aovs:
// from the centres' item buffer where the source has one, else by camera ray. Returns the rays.
RayCounts centre_aovs(const World& world, const PrimarySource& source, const TileRect& r,
                      RenderResult& result) {
    const PinholeCamera& camera = world.camera();
    const PrimarySource centres{source.ids, source.resolve};
    PrimaryStats unused; // the AOVs' own rays: not the frame's resolve figures
    RayCounts counts;
    for (int y = r.y0; y < r.y1; ++y) {
        for (int x = r.x0; x < r.x1; ++x) {
            const Ray ray = camera.ray(x, y);
            const Hit hit = primary_hit(world, centres, x, y, ray, unused);
            const Vec3 normal = hit.found() ? world.surface(ray, hit).shading : Vec3(0);
            store_aovs(result, static_cast<std::size_t>(y) * camera.width() + x, hit, normal);
            ++counts.primary;
        }
    }
    return counts;
}

// The grids pass on one tile: each pixel's N×N grid mean (every pixel, or only where `only` is
// 1) by grid_hits and shade_grid, its cut-off weight the samples' mean; with every pixel, its id
// the grid's sample (N/2, N/2), and the centres' AOVs where the result keeps them.
TileFigures grids_tile(const World& world, const PrimarySource& source,
                       const std::vector<std::uint8_t>* only, const TileRect& r,
                       RenderResult& result) {
    TileFigures figures;
    Stopwatch watch;
    const int width = world.camera().width(), n = world.settings().samples;
    const std::size_t grid = static_cast<std::size_t>(n) * n;
    TileBuffers& buffers = tile_buffers();
    std::vector<std::size_t>& pixels = buffers.pixels; // the tile's pixels to sample, in row order
    std::vector<Hit>& hits = buffers.hits; // their grids' primary hits, one grid after another
    pixels.clear(), hits.clear();
    for (int y = r.y0; y < r.y1; ++y) {
        for (int x = r.x0; x < r.x1; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (only && !(*only)[i]) continue;
            pixels.push_back(i);
            hits.resize(hits.size() + grid);
            grid_hits(world, source, x, y, &hits[hits.size() - grid], figures.stats);
        }
    }
    if (!only && !result.aovs.empty()) figures.rays += centre_aovs(world, source, r, result);
    figures.primary = watch.lap();
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const std::size_t i = pixels[k];
        const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
        const GridPixel pixel = shade_grid(world, x, y, &hits[k * grid]);
        store_pixel(result, i, pixel.radiance, pixel.mean);
        result.set_omitted(i, static_cast<float>(pixel.omitted_weight));
        if (!only && !result.ids.empty()) result.ids[i] = pixel.centre_id;
        figures.rays += pixel.rays;
    }
    figures.shading = watch.lap();
    return figures;
}

// Runs one pass through the schedule: each tile's figures summed into `result` and `stats`, the
// pass's wall time shared between times.primary and times.shading in the ratio of its tiles'
// summed times for each. The pass writes `keys` where given, and only the pixels of `only`
// where given. False when cancelled.
template <class Tile>
bool run_pass(TileSchedule& schedule, FramePass pass, RenderResult& result, PrimaryStats& stats,
              PhaseTimes& times, std::vector<std::uint64_t>* keys,
              const std::vector<std::uint8_t>* only, const Tile& tile) {
    schedule.open(pass, result, keys, only);
    std::mutex mutex;
    double primary = 0, shading = 0;
    const Stopwatch wall;
    const bool complete = schedule.run(pass, result, [&](const TileRect& rect) {
        const TileFigures f = tile(rect);
        const std::lock_guard lock(mutex); // integer sums: order does not matter
        result.rays += f.rays, stats += f.stats;
        primary += f.primary, shading += f.shading;
        return f.rays;
    });
    times.add_split(wall.seconds(), primary, shading);
    return complete;
}

// The bytes of the pixels marked in `which`, from `result` into `bytes`.
void copy_bytes(const RenderResult& result, const std::vector<std::uint8_t>& which, Image& bytes) {
    for (std::size_t i = 0; i < which.size(); ++i)
        if (which[i])
            for (int c = 0; c < 3; ++c) bytes.rgb[3 * i + c] = result.byte_at(i, c);
}

} // namespace

RenderResult run_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                       TileSchedule& schedule, PhaseTimes& times, const FrameRequest& request) {
    const RenderSettings& settings = world.settings();
    RenderResult result = blank_result(world, settings.samples, request);
    const bool uniform = settings.samples > 1 && settings.antialias == Antialias::uniform;
    const bool adaptive = settings.samples > 1 && !uniform;
    const auto grids = [&](FramePass pass, const std::vector<std::uint8_t>* only) {
        const bool complete =
            run_pass(schedule, pass, result, stats, times, nullptr, only, [&](const TileRect& r) {
                return grids_tile(world, source, only, r, result);
            });
        if (complete) schedule.finish(pass, result), ++result.passes;
        return complete;
    };

    if (!uniform || request.centres_first) {
        std::vector<std::uint64_t> path_keys(adaptive ? result.pixels() : 0);
        std::vector<std::uint64_t>* keys = adaptive ? &path_keys : nullptr;
        if (!run_pass(schedule, FramePass::centres, result, stats, times, keys, nullptr,
                      [&](const TileRect& r) {
                          return centres_tile(world, source, r, result, keys, request.observer);
                      }))
            return result;
        schedule.finish(FramePass::centres, result);
        ++result.passes;
        if (adaptive) {
            // Rules 1 to 3 (trace/sampling.h) pick the pixels from the first pass's bytes, where
            // the whole image is: in one process, or on the rank that gathers the others' tiles,
            // which hands its picks to them (schedule.agree).
            const bool decides = schedule.decides();
            const Image first = decides ? result.bytes() : Image();
            result.refined = timed(times.shading, [&] {
                return decides ? adaptive_refinement(first, path_keys, source.sample_ids,
                                                     settings.samples, settings.aa_threshold)
                               : std::vector<std::uint8_t>();
            });
            schedule.agree(FramePass::grids, result.refined);
            if (!grids(FramePass::grids, &result.refined)) return result;
            // Rule 4, round by round; the rounds' scans count as shading, each pass times itself.
            const double timed_before = times.primary + times.shading;
            const Stopwatch rounds;
            Image current = first;
            if (decides) copy_bytes(result, result.refined, current);
            spread_refinement(
                first, current, result.refined, settings.aa_threshold, decides,
                [&](std::vector<std::uint8_t>& next) { schedule.agree(FramePass::spread, next); },
                [&](const std::vector<std::uint8_t>& next) {
                    if (!grids(FramePass::spread, &next)) return false;
                    if (decides) copy_bytes(result, next, current);
                    return true;
                });
            times.shading += rounds.seconds() - (times.primary + times.shading - timed_before);
            return result;
        }
    }
    if (uniform) grids(FramePass::grids, nullptr);
    return result;
}

} // namespace GLINT_PRECISION
} // namespace glint
