// The frame's last phase: shade every pixel from its primary hit (found by ray or from the item
// buffer, trace/primary_hits.h), in parallel tiles; byte-identical for any thread count.
#pragma once

#include "trace/image.h"
#include "trace/primary_hits.h"
#include "trace/shading.h"

namespace glint {

struct RenderResult {
    Image image;
    RayCounts rays;
};

// Shades the pixels whose primary hits are given (row-major, top row first).
RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress = {});

// Ray mode in one call: primary hits by ray casting, then shading.
RenderResult render(const World& world, const TileProgress& progress = {});

} // namespace glint
