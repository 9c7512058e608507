// The frame's last phase: shade every pixel from its primary hit (found by ray or from the item
// buffer, trace/primary_hits.h), in parallel tiles; byte-identical for any thread count.
#pragma once

#include "trace/image_metrics.h"
#include "trace/passes.h"
#include "trace/pixel.h"
#include "trace/render_result.h"

namespace glint {
inline namespace GLINT_PRECISION {

// Writes a shaded colour as a pixel's three bytes (trace/image.h's to_byte per channel).
inline void store_colour(Vec3 c, std::uint8_t* pixel) {
    for (int i = 0; i < 3; ++i) pixel[i] = to_byte(static_cast<float>(c[i]));
}

// Stores pixel i's colour, the mean of its samples: unclamped, and with each sample clamped
// where the result keeps that apart (N > 1).
inline void store_pixel(RenderResult& result, std::size_t i, Vec3 radiance, Vec3 clamped) {
    result.radiance.set(i, radiance);
    if (!result.clamped.empty()) result.clamped.set(i, clamped);
}

// Stores what pixel i's centre ray hit, where the result keeps its AOVs.
inline void store_aovs(RenderResult& result, std::size_t i, const Hit& hit, Vec3 normal) {
    if (result.aovs.empty() || !hit.found()) return;
    result.aovs.depth[i] = static_cast<float>(hit.t);
    for (int k = 0; k < 3; ++k) result.aovs.normal[3 * i + k] = static_cast<float>(normal[k]);
    result.aovs.id[i] = hit.object + 1;
}

// An empty result for `camera`'s image: the clamped image where a pixel's samples are N > 1,
// the AOVs where asked for.
RenderResult blank_result(const PinholeCamera& camera, int samples, bool aovs);

// A worker thread's buffers for the tile it works on, kept from tile to tile (tile_buffers()).
// Allocated anew for each tile, they cost small scenes up to two thirds of their shading time:
// glibc gives the free memory at the top of its heap back to the kernel once more than 128 KB
// lie there, and the next tile's first touch of each of those pages is a page fault
// (docs/PERFORMANCE.md, "Tile buffers and huge pages").
struct TileBuffers {
    std::vector<Hit> primary;        // the centres pass: the tile's primary hits
    std::vector<std::size_t> pixels; // the pixels being shaded, in the order shaded
    std::vector<Ray> rays;           // their camera rays
    std::vector<Hit> hits;           // their primary hits (the grids pass: grid after grid)
    TileLighting lighting;           // their surfaces and shadow verdicts
};

// The calling thread's TileBuffers. A tile's work uses them until it returns; a thread works on
// one tile at a time (nothing in a tile's work waits on other tasks, so none is run meanwhile).
TileBuffers& tile_buffers();

// Shades tile r's pixels from their primary hits (pixel (x, y)'s at primary[(y − r.y0)·stride +
// (x − r.x0)], as tile_primary_hits leaves them) into `result`: colour, cut-off weight, id, AOVs
// where kept, and with `path_keys` each pixel's RayTree::path_key; shows each to `observer`
// where given. Returns the rays cast. The pixels go in blocks, so that their shadow rays go in
// packets of neighbours (TileLighting).
RayCounts shade_tile(const World& world, const Hit* primary, std::size_t stride, const TileRect& r,
                     RenderResult& result, std::vector<std::uint64_t>* path_keys,
                     CentreObserver* observer = nullptr);

// Shades the pixels whose primary hits are given (row-major, top row first), each through
// trace/pixel.h's path, one sample at each pixel's centre; with `path_keys`, also stores each
// pixel's RayTree::path_key there.
RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress = {},
                         std::vector<std::uint64_t>* path_keys = nullptr);

// The tracer's part of every frame on this process's threads (or its share of tiles across
// processes, progress.exchange): trace/passes.h's run_frame with a ThreadSchedule, primary hits
// from `source` (frame/frame.h draws the item buffer before it in hybrid mode), each phase timed
// into `times`.
// With `aovs`, also keeps each pixel centre's primary hit (RenderResult::aovs).
RenderResult trace_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                         const TileProgress& progress, PhaseTimes& times, bool aovs = false);

// Ray mode in one call: primary hits by ray casting, then shading, with the scene's samples.
RenderResult render(const World& world, const TileProgress& progress = {});

// Object index + 1 per pixel, 0 where the primary ray hit nothing.
std::vector<std::uint32_t> object_ids(const std::vector<Hit>& primary);

} // namespace GLINT_PRECISION
} // namespace glint
