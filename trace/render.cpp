#include "trace/render.h"

#include "trace/image_metrics.h"
#include "trace/passes.h"
#include "trace/stopwatch.h"

#include <mutex>

namespace glint {
inline namespace GLINT_PRECISION {

RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress, std::vector<std::uint64_t>* path_keys) {
    RenderResult result = blank_result(world, 1, {});
    if (path_keys) path_keys->assign(primary.size(), 0);
    std::mutex counts_mutex;
    for_each_tile(result.width(), result.height(), progress,
                  [&](int x0, int y0, int x1, int y1) {
                      const std::size_t width = static_cast<std::size_t>(result.width());
                      const RayCounts counts =
                          shade_tile(world, &primary[static_cast<std::size_t>(y0) * width + x0],
                                     width, {x0, y0, x1, y1}, result, path_keys);
                      const std::lock_guard lock(counts_mutex); // integer sums: any order
                      result.rays += counts;
                  });
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
                         const TileProgress& progress, PhaseTimes& times,
                         const FrameRequest& request) {
    ThreadSchedule schedule(progress);
    return run_frame(world, source, stats, schedule, times, request);
}

RenderResult render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                              const TileProgress& progress, PhaseTimes& times) {
    const World world = timed(times.prepare, [&] { return World(scene, accel); });
    PrimaryStats unused; // counted only when resolving ids
    return trace_frame(world, {}, unused, progress, times);
}

} // namespace GLINT_PRECISION
} // namespace glint
