// The tile loop shared by every per-pixel phase: 2D tiles scheduled by oneTBB, one tile per task
// (tiles differ a lot in cost: sky versus mirrors). Pixels never depend on each other, so the
// result is the same for any thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "trace/names.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

namespace glint {

inline constexpr int kTileSize = 32;

struct RenderResult; // trace/render_result.h

// A frame's passes, in their order (trace/passes.h says what each does).
enum class FramePass { centres, grids, spread };

template <> struct EnumNames<FramePass> {
    static constexpr auto names = name_table("centres", "grids", "spread");
};

// One frame rendered by several processes (docs/DISTRIBUTED.md). Every tile loop of the frame
// hands its tiles out as the processes ask for them (`claim`: the next tile nobody has taken in
// this loop, from a counter they share), so that a process that is slowed down takes fewer. Each
// tile a process traces goes to the one process that decides (rank 0) as soon as it is done
// (`traced`), while the loop goes on; `close` waits for the last. The deciding process alone
// holds the whole image, writes it, and decides which pixels a later loop refines (adaptive
// antialiasing reads neighbours across tile borders); `agree` hands that decision to the others.
// A loop's tiles must need nothing but the image before it: trace_frame fuses primary hits and
// shading into one loop for this (trace/render.cpp).
class TileExchange {
  public:
    virtual ~TileExchange() = default;
    // Before a loop: the frame its tiles write (each layer it keeps), `keys` where the loop
    // writes them, and `only`: the pixels it refines (null: every pixel of a tile).
    virtual void open(FramePass pass, RenderResult& result, std::vector<std::uint64_t>* keys,
                      const std::vector<std::uint8_t>* only) = 0;
    // The loop's next tile, or −1 once every tile of the loop is taken; any thread may ask.
    virtual int claim() = 0;
    // After this process traced `tile`: its pixels (those the loop wrote) on their way to the
    // deciding process. Any thread may call it.
    virtual void traced(int tile) = 0;
    // After the loop: every process's pixels are in the deciding one's frame; the next loop's
    // tiles are handed out afresh.
    virtual void close() = 0;
    // Whether this process holds the whole image after each loop, and decides.
    virtual bool decides() const = 0;
    // The deciding process's `mask` (the pixels the next loop refines) in every process's `mask`.
    virtual void agree(FramePass pass, std::vector<std::uint8_t>& mask) = 0;
    // The tiles this process claimed, all loops (once the frame is done).
    virtual int tiles_taken() const = 0;
};

struct TileProgress {
    int threads = 0;                        // 0: all cores
    std::atomic<int>* tiles_done = nullptr; // counted as tiles finish
    TileExchange* exchange = nullptr;       // one process of several: its tiles only
    // Set from outside (Python's Ctrl-C): tiles not yet started are skipped, and the frame's
    // passes stop (TileSchedule::run returns false). Null: never cancelled.
    const std::atomic<bool>* cancel = nullptr;
    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
};

inline int tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
}

// Pixels [x0, x1)×[y0, y1) of an image.
struct TileRect {
    int x0, y0, x1, y1;
    std::size_t pixels() const { return static_cast<std::size_t>(x1 - x0) * (y1 - y0); }
};

// Tile `tile` of a width×height image, tiles numbered row by row from the top left: the one
// place that turns a tile's number into its pixels.
inline TileRect tile_rect(int width, int height, int tile) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
    return {x0, y0, std::min(x0 + kTileSize, width), std::min(y0 + kTileSize, height)};
}

// Calls visit(i) for each pixel index (y·width + x) of tile `tile`, row by row.
template <class Visit> void for_each_pixel_of_tile(int width, int height, int tile, const Visit& visit) {
    const TileRect r = tile_rect(width, height, tile);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) visit(static_cast<std::size_t>(y) * width + x);
}

// Whether pred(nx, ny) holds for any pixel of the 3×3 neighbourhood of (x, y) (itself included)
// that lies inside a width×height image; stops at the first that does. The exact resolve's edge
// test and the adaptive antialiasing rule (trace/sampling.cpp) read neighbourhoods this way.
template <class Pred>
bool any_in_neighbourhood(int width, int height, int x, int y, const Pred& pred) {
    for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx)
            if (pred(nx, ny)) return true;
    return false;
}

// A packet of camera rays (or of their shadow rays): a block of kBlockSize² neighbouring pixels.
inline constexpr int kBlockSize = 4;

// Calls body(x, y) for the pixels of [x0, x1)×[y0, y1) block by block (kBlockSize² pixels, row by
// row within a block): the order a tile's packets take its pixels in.
template <class Body> void for_each_in_blocks(int x0, int y0, int x1, int y1, const Body& body) {
    for (int by = y0; by < y1; by += kBlockSize)
        for (int bx = x0; bx < x1; bx += kBlockSize)
            for (int y = by; y < std::min(by + kBlockSize, y1); ++y)
                for (int x = bx; x < std::min(bx + kBlockSize, x1); ++x) body(x, y);
}

// Calls body(x0, y0, x1, y1) for each tile of a width×height image, in parallel. With an
// exchange, for the tiles this process claims (each iteration asks for the next tile instead of
// taking its own index). Once progress.cancel is set, the tiles not yet begun are skipped.
template <class Body>
void for_each_tile(int width, int height, const TileProgress& progress, const Body& body) {
    TileExchange* const exchange = progress.exchange;
    tbb::task_arena arena(progress.threads > 0 ? progress.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, tile_count(width, height), 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int index = r.begin(); index != r.end(); ++index) {
                    if (progress.cancelled()) return;
                    int tile = index;
                    if (exchange && (tile = exchange->claim()) < 0) continue;
                    const TileRect rect = tile_rect(width, height, tile);
                    body(rect.x0, rect.y0, rect.x1, rect.y1);
                    if (exchange) exchange->traced(tile);
                    if (progress.tiles_done)
                        progress.tiles_done->fetch_add(1, std::memory_order_relaxed);
                }
            });
    });
}

} // namespace glint
