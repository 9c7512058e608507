// The tile loop shared by every per-pixel phase: 2D tiles scheduled by oneTBB, one tile per task
// (tiles differ a lot in cost: sky versus mirrors). Pixels never depend on each other, so the
// result is the same for any thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>

namespace glint {

inline constexpr int kTileSize = 32;

struct TileProgress {
    int threads = 0;                        // 0: all cores
    std::atomic<int>* tiles_done = nullptr; // counted as tiles finish
};

inline int tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

// Calls body(x0, y0, x1, y1) for each tile of a width×height image, in parallel.
template <class Body>
void for_each_tile(int width, int height, const TileProgress& progress, const Body& body) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    tbb::task_arena arena(progress.threads > 0 ? progress.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, tile_count(width, height), 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int tile = r.begin(); tile != r.end(); ++tile) {
                    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                    body(x0, y0, std::min(x0 + kTileSize, width), std::min(y0 + kTileSize, height));
                    if (progress.tiles_done)
                        progress.tiles_done->fetch_add(1, std::memory_order_relaxed);
                }
            });
    });
}

} // namespace glint
