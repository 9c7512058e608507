#include "trace/render.h"

#include "trace/image_metrics.h"

#include "trace/stopwatch.h"

#include <mutex>

namespace glint {
inline namespace GLINT_PRECISION {

RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width();
    RenderResult result{Image(width, camera.height()), {}, {}, object_ids(primary)};
    result.omitted_weight.assign(primary.size(), 0.0f);
    std::mutex counts_mutex;
    for_each_tile(width, camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        RayCounts counts;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * width + x;
                const PixelSample sample = shade_pixel(world, camera.ray(x, y), primary[i]);
                result.omitted_weight[i] = static_cast<float>(sample.omitted_weight);
                store_colour(sample.colour, result.image.pixel(x, y));
                counts += sample.rays;
            }
        }
        const std::lock_guard lock(counts_mutex); // integer sums: order does not matter
        result.rays += counts;
    });
    return result;
}

RenderResult render(const World& world, const TileProgress& progress) {
    return shade_image(world, primary_hits_by_ray(world, progress), progress);
}

std::vector<std::uint32_t> object_ids(const std::vector<Hit>& primary) {
    std::vector<std::uint32_t> ids(primary.size());
    for (std::size_t i = 0; i < primary.size(); ++i)
        ids[i] = primary[i].found() ? primary[i].object + 1 : 0;
    return ids;
}

RenderResult trace_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                         const TileProgress& progress, PhaseTimes& times) {
    const std::vector<Hit> primary =
        timed(times.primary, [&] { return primary_hits(world, source, stats, progress); });
    return timed(times.shading, [&] { return shade_image(world, primary, progress); });
}

RenderResult render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                              const TileProgress& progress, PhaseTimes& times) {
    const World world = timed(times.prepare, [&] { return World(scene, accel); });
    PrimaryStats unused; // counted only when resolving ids
    return trace_frame(world, {}, unused, progress, times);
}

} // namespace GLINT_PRECISION
} // namespace glint
