// The render loop: primary rays through every pixel centre, in 2D tiles, in parallel (oneTBB).
// Every pixel is computed independently, so the image is byte-identical for any thread count.
#pragma once

#include "trace/image.h"
#include "trace/shading.h"

#include <atomic>

namespace glint {

inline constexpr int kTileSize = 32;

struct RenderOptions {
    int threads = 0;                        // 0: all cores
    std::atomic<int>* tiles_done = nullptr; // progress, counted as tiles finish
};

struct RenderResult {
    Image image;
    RayCounts rays;
};

int tile_count(int width, int height);

RenderResult render(const World& world, const RenderOptions& options = {});

} // namespace glint
