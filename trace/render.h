// A whole frame on this process's threads: trace/passes.h's run_frame with a ThreadSchedule,
// and the calls built on it (ray mode in one call, a frame shaded from given primary hits);
// byte-identical for any thread count.
#pragma once

#include "trace/image_metrics.h"
#include "trace/passes.h"
#include "trace/pixel.h"
#include "trace/render_result.h"
#include "trace/tile_shading.h"

namespace glint {
inline namespace GLINT_PRECISION {

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
// `request` names the layers it keeps besides the image (the AOVs, the ids).
RenderResult trace_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                         const TileProgress& progress, PhaseTimes& times,
                         const FrameRequest& request = {});

// Ray mode in one call: primary hits by ray casting, then shading, with the scene's samples.
RenderResult render(const World& world, const TileProgress& progress = {});

// Object index + 1 per pixel, 0 where the primary ray hit nothing.
std::vector<std::uint32_t> object_ids(const std::vector<Hit>& primary);

} // namespace GLINT_PRECISION
} // namespace glint
