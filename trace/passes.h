// A frame's passes, in their order, written once for every way a frame is traced:
//   centres  each pixel centre's primary hit and shading, tile by tile (N = 1's image, and
//            adaptive antialiasing's first pass);
//   grids    the N×N sample grids (trace/sampling.h): every pixel (uniform), or the pixels the
//            adaptive rule picks from the first pass;
//   spread   the adaptive rule's last part, round by round, until it adds nothing.
// The tiles of each pass are handed out by a TileSchedule: oneTBB threads in one process, tiles
// claimed across MPI ranks (each traced tile sent to rank 0, which decides), or the preview's
// workers, which show each tile as it finishes and stop when the camera moves.
#pragma once

#include "trace/pixel.h"
#include "trace/render_result.h"
#include "trace/tile_shading.h"

#include <functional>

namespace glint {

inline namespace GLINT_PRECISION {

// A pass's work on one tile; returns the rays it cast.
using TileWork = std::function<RayCounts(const TileRect&)>;

// Who traces a pass's tiles, and what happens after each pass.
class TileSchedule {
  public:
    virtual ~TileSchedule() = default;
    // Calls work(tile) once for each tile of `result`'s image (any order, any thread), and
    // returns true once all are done, or false when the frame was cancelled (some were not).
    // `result` may be read for a tile once its work is done.
    virtual bool run(FramePass pass, const RenderResult& result, const TileWork& work) = 0;
    // Before a pass's first tile: what its tiles write (`result`, and `keys` where given; only
    // the pixels marked in `only`, where given), for a schedule that sends tiles elsewhere.
    virtual void open(FramePass, RenderResult&, std::vector<std::uint64_t>*,
                      const std::vector<std::uint8_t>*) {}
    // After a pass's last tile, before anything reads its pixels: several processes have sent
    // what the pass changed (as open() named it) to the one that decides.
    virtual void finish(FramePass, RenderResult&) {}
    // Whether this process holds the whole image after finish, and decides what later passes
    // refine; the others take its decision from agree().
    virtual bool decides() const { return true; }
    // The deciding process's `mask` in every process's.
    virtual void agree(FramePass, std::vector<std::uint8_t>&) {}
};

// This process's threads (oneTBB), or with progress.exchange its share of tiles claimed across
// processes, gathered on the deciding one after each pass; tiles of the centres and grids passes are counted in
// progress.tiles_done.
class ThreadSchedule final : public TileSchedule {
  public:
    explicit ThreadSchedule(const TileProgress& progress) : progress_(progress) {}
    bool run(FramePass pass, const RenderResult& result, const TileWork& work) override;
    void open(FramePass pass, RenderResult& result, std::vector<std::uint64_t>* keys,
              const std::vector<std::uint8_t>* only) override {
        if (progress_.exchange) progress_.exchange->open(pass, result, keys, only);
    }
    void finish(FramePass pass, RenderResult& result) override;
    bool decides() const override { return !progress_.exchange || progress_.exchange->decides(); }
    void agree(FramePass pass, std::vector<std::uint8_t>& mask) override {
        if (progress_.exchange) progress_.exchange->agree(pass, mask);
    }

  private:
    TileProgress progress_;
};

// FrameRequest, what a frame keeps besides its colours: trace/tile_shading.h.

// The frame of `world`, primary hits from `source`, its passes' tiles traced by `schedule`,
// each pass's primary-hit and shading parts timed into `times`. A cancelled frame returns what
// it had.
RenderResult run_frame(const World& world, const PrimarySource& source, PrimaryStats& stats,
                       TileSchedule& schedule, PhaseTimes& times, const FrameRequest& request = {});

// How many tiles a ThreadSchedule counts in progress.tiles_done over a frame of this size.
int progress_steps(const RenderSettings& settings, int width, int height);

} // namespace GLINT_PRECISION
} // namespace glint
