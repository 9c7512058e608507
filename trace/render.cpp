#include "trace/render.h"

#include "trace/image_metrics.h"
#include "trace/sampling.h"
#include "trace/stopwatch.h"

#include <mutex>

namespace glint {
inline namespace GLINT_PRECISION {

RenderResult blank_result(const PinholeCamera& camera, int samples, bool aovs) {
    const int width = camera.width(), height = camera.height();
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    RenderResult result;
    result.radiance = FloatImage(width, height);
    if (samples > 1) result.clamped = FloatImage(width, height);
    result.omitted_weight.assign(pixels, 0.0f);
    result.ids.assign(pixels, 0);
    if (aovs) result.aovs = PrimaryAovs(pixels);
    return result;
}

namespace {

// Shades tile [x0, x1)×[y0, y1) from its primary hits into `result` (and `path_keys`, where
// given); returns the rays it cast. The tile's pixels go in blocks, so that its shadow rays go in
// packets of neighbours.
RayCounts shade_tile(const World& world, const std::vector<Hit>& primary, int x0, int y0, int x1,
                     int y1, RenderResult& result, std::vector<std::uint64_t>* path_keys) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width();
    std::vector<std::size_t> pixels;
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    for_each_in_blocks(x0, y0, x1, y1, [&](int x, int y) {
        pixels.push_back(static_cast<std::size_t>(y) * width + x);
        rays.push_back(camera.ray(x, y));
        hits.push_back(primary[pixels.back()]);
    });
    const TileLighting lighting(world, rays, hits);
    RayCounts counts;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const std::size_t i = pixels[k];
        const PixelSample sample = shade_pixel(world, rays[k], hits[k], lighting.at(k));
        result.omitted_weight[i] = static_cast<float>(sample.omitted_weight);
        if (path_keys) (*path_keys)[i] = sample.path_key;
        store_pixel(result, i, sample.colour, glm::clamp(sample.colour, Vec3(0), Vec3(1)));
        store_aovs(result, i, sample.hit, sample.normal);
        counts += sample.rays;
    }
    return counts;
}

// One process of several (progress.exchange): primary hits and shading tile by tile in one loop,
// so that the tiles it claims need nothing from another process; the two phases' shares of the
// loop's wall time as their summed tile times say.
void trace_claimed_tiles(const World& world, const PrimarySource& source, PrimaryStats& stats,
                         const TileProgress& progress, PhaseTimes& times, RenderResult& result,
                         std::vector<std::uint64_t>* path_keys) {
    const PinholeCamera& camera = world.camera();
    std::vector<Hit> primary(static_cast<std::size_t>(camera.width()) * camera.height());
    std::mutex mutex;
    double primary_seconds = 0, shading_seconds = 0;
    const Stopwatch wall;
    for_each_tile(camera.width(), camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        Stopwatch watch;
        PrimaryStats local;
        tile_primary_hits(world, source, x0, y0, x1, y1, primary, local);
        const double hits_seconds = watch.lap();
        const RayCounts counts = shade_tile(world, primary, x0, y0, x1, y1, result, path_keys);
        const double shade_seconds = watch.lap();
        const std::lock_guard lock(mutex); // integer sums: order does not matter
        stats += local, result.rays += counts;
        primary_seconds += hits_seconds, shading_seconds += shade_seconds;
    });
    result.ids = object_ids(primary); // the other processes' tiles come with the exchange
    times.add_split(wall.seconds(), primary_seconds, shading_seconds);
}

// Shades every pixel from its primary hit into `result`.
void shade_into(const World& world, const std::vector<Hit>& primary, const TileProgress& progress,
                RenderResult& result, std::vector<std::uint64_t>* path_keys) {
    const PinholeCamera& camera = world.camera();
    result.ids = object_ids(primary);
    std::mutex counts_mutex;
    for_each_tile(camera.width(), camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        const RayCounts counts = shade_tile(world, primary, x0, y0, x1, y1, result, path_keys);
        const std::lock_guard lock(counts_mutex); // integer sums: order does not matter
        result.rays += counts;
    });
}

} // namespace

RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress, std::vector<std::uint64_t>* path_keys) {
    const PinholeCamera& camera = world.camera();
    RenderResult result = blank_result(camera, 1, false);
    if (path_keys) path_keys->assign(primary.size(), 0);
    shade_into(world, primary, progress, result, path_keys);
    return result;
}

RenderResult render(const World& world, const TileProgress& progress) {
    PrimaryStats unused;
    PhaseTimes times;
    return trace_frame(world, {}, unused, progress, times);
}

std::vector<std::uint32_t> object_ids(const std::vector<Hit>& primary) {
    std::vector<std::uint32_t> ids(primary.size());
    for (std::size_t i = 0; i < primary.size(); ++i)
        ids[i] = primary[i].found() ? primary[i].object + 1 : 0;
    return ids;
}

RenderResult trace_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                         const TileProgress& progress, PhaseTimes& times, bool aovs) {
    const RenderSettings& settings = world.settings();
    RenderResult result = blank_result(world.camera(), settings.samples, aovs);
    // Several processes: after each pass every process gets the others' tiles.
    const auto share = [&](RenderResult& shared, std::vector<std::uint64_t>* keys) {
        if (progress.exchange) progress.exchange->share(shared, keys);
    };
    if (settings.samples > 1 && settings.antialias == Antialias::uniform) {
        render_uniform_grids(world, source, stats, progress, times, result);
        share(result, nullptr);
        return result;
    }
    // One sample per pixel, at its centre: the whole image with N = 1, and adaptive
    // antialiasing's first pass.
    const bool adaptive = settings.samples > 1;
    std::vector<std::uint64_t> path_keys;
    if (adaptive) path_keys.assign(result.ids.size(), 0);
    std::vector<std::uint64_t>* keys = adaptive ? &path_keys : nullptr;
    if (progress.exchange) {
        trace_claimed_tiles(world, source, stats, progress, times, result, keys);
    } else {
        const std::vector<Hit> primary =
            timed(times.primary, [&] { return primary_hits(world, source, stats, progress); });
        timed(times.shading, [&] {
            shade_into(world, primary, progress, result, keys);
            return 0;
        });
    }
    share(result, keys);
    if (adaptive) refine_adaptively(world, source, path_keys, result, stats, progress, times);
    return result;
}

int progress_steps(const RenderSettings& settings, int width, int height) {
    const bool adaptive = settings.samples > 1 && settings.antialias == Antialias::adaptive;
    return (adaptive ? 4 : 2) * tile_count(width, height);
}

RenderResult render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                              const TileProgress& progress, PhaseTimes& times) {
    const World world = timed(times.prepare, [&] { return World(scene, accel); });
    PrimaryStats unused; // counted only when resolving ids
    return trace_frame(world, {}, unused, progress, times);
}

} // namespace GLINT_PRECISION
} // namespace glint
