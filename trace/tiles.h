// The tile loop shared by every per-pixel phase: 2D tiles scheduled by oneTBB, one tile per task
// (tiles differ a lot in cost: sky versus mirrors). Pixels never depend on each other, so the
// result is the same for any thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

namespace glint {

inline constexpr int kTileSize = 32;

struct RenderResult; // trace/precision.h

// One frame rendered by several processes (docs/DISTRIBUTED.md): this one, `rank` of `ranks`,
// traces tiles rank, rank + ranks, rank + 2·ranks, … (interleaved, so that every process gets
// tiles from every part of the image), and after each pass `share` gives every process the
// others' pixels, so that a pass that reads its neighbours (adaptive antialiasing) reads the
// whole image, as in one process.
class TileExchange {
  public:
    TileExchange(int rank, int ranks) : rank_(rank), ranks_(ranks) {}
    virtual ~TileExchange() = default;
    int rank() const { return rank_; }
    int ranks() const { return ranks_; }
    bool owns(int tile) const { return tile % ranks_ == rank_; }
    // After a pass over this process's tiles: their pixels of `result` (colour, cut-off weight,
    // id) and of `keys` (where given) to every process, the others' into this one's.
    virtual void share(RenderResult& result, std::vector<std::uint64_t>* keys) const = 0;

  private:
    int rank_, ranks_;
};

struct TileProgress {
    int threads = 0;                        // 0: all cores
    std::atomic<int>* tiles_done = nullptr; // counted as tiles finish
    const TileExchange* exchange = nullptr; // one process of several: its tiles only
};

inline int tile_count(int width, int height) {
    return ((width + kTileSize - 1) / kTileSize) * ((height + kTileSize - 1) / kTileSize);
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

// Calls body(x0, y0, x1, y1) for each tile of a width×height image (each this process owns, with
// an exchange), in parallel.
template <class Body>
void for_each_tile(int width, int height, const TileProgress& progress, const Body& body) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    tbb::task_arena arena(progress.threads > 0 ? progress.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, tile_count(width, height), 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int tile = r.begin(); tile != r.end(); ++tile) {
                    if (progress.exchange && !progress.exchange->owns(tile)) continue;
                    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                    body(x0, y0, std::min(x0 + kTileSize, width), std::min(y0 + kTileSize, height));
                    if (progress.tiles_done)
                        progress.tiles_done->fetch_add(1, std::memory_order_relaxed);
                }
            });
    });
}

} // namespace glint
