#include "trace/render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <mutex>

namespace glint {

int tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

RenderResult render(const World& world, const RenderOptions& options) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width(), height = camera.height();
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    RenderResult result{Image(width, height), {}};
    std::mutex counts_mutex;

    const auto render_tile = [&](int tile) {
        const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
        const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
        RayCounts counts;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const Vec3 c = trace_primary(world, camera.ray(x, y), counts);
                std::uint8_t* p = result.image.pixel(x, y);
                p[0] = to_byte(c.x), p[1] = to_byte(c.y), p[2] = to_byte(c.z);
            }
        }
        {
            const std::lock_guard lock(counts_mutex); // integer sums: order does not matter
            result.rays += counts;
        }
        if (options.tiles_done) options.tiles_done->fetch_add(1, std::memory_order_relaxed);
    };

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        // One tile per task: tiles differ a lot in cost (sky versus mirrors).
        tbb::parallel_for(tbb::blocked_range<int>(0, tile_count(width, height), 1),
                          [&](const tbb::blocked_range<int>& range) {
                              for (int tile = range.begin(); tile != range.end(); ++tile)
                                  render_tile(tile);
                          });
    });
    return result;
}

} // namespace glint
