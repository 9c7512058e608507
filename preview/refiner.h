// Progressive tracing for the preview: one job per camera and settings, whose frame runs through
// trace/passes.h's run_frame like every render, its tiles handed out from the image centre
// outwards to worker threads (PreviewSchedule below), while the UI thread shows each tile as it
// finishes. A job is cancelled (between tiles) as soon as the camera moves. A finished job is
// the headless image. With the scene's samples N > 1 it shows the passes one after another: the
// pixel centres first (a first look, which uniform antialiasing's render skips), then the grids,
// then with adaptive antialiasing the spreading, shown once its rounds are done.
#pragma once

#include "preview/views.h"

#include "trace/passes.h"
#include "trace/stopwatch.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

class RefineJob final : private CentreObserver {
  public:
    // `ids`: the item buffer for hybrid resolve; null traces every primary ray (ray mode).
    // `compare_with_ray`: also cast every camera ray in hybrid mode, for the difference view
    // (otherwise that view shows no difference and no ray is spent on it).
    RefineJob(std::shared_ptr<const World> world, std::shared_ptr<const IdImage> ids,
              Resolve resolve, bool compare_with_ray = false);

    bool compares_with_ray() const { return compare_with_ray_; }
    int width() const { return final_.width; }
    int height() const { return final_.height; }

    // The traced image of a view (is_traced(view)) as `passes` passes leave it (default: all);
    // read a tile's pixels only once tile_passes says that many are done. Each pass writes its
    // own copy of the final view, so a tile shown after one pass is never written again.
    const Image& traced(View view, int passes = 3) const;
    int tile_count() const { return static_cast<int>(order_.size()); } // per pass
    TileRect tile(int index) const;                                    // in row-major tile order
    int passes() const { return passes_; }
    // How many passes have finished tile `index` (0 … passes()).
    int tile_passes(int index) const { return done_[index].load(std::memory_order_acquire); }
    bool tile_done(int index) const { return tile_passes(index) > 0; }
    int tiles_done() const { return tiles_done_.load(std::memory_order_acquire); } // all passes
    // Every pass of every tile done, and the frame's totals stored.
    bool finished() const { return complete_.load(std::memory_order_acquire); }
    // Pixels the grids refine (all with uniform antialiasing); 0 before they start.
    std::uint64_t refined_pixels() const;
    // Whether pixel (x, y) took its grid (adaptive antialiasing, all passes); read once finished.
    bool refined(int x, int y) const {
        return !refined_map_.empty() && refined_map_[static_cast<std::size_t>(y) * width() + x];
    }

    // Traces the frame on `threads` workers until it is done or `cancel` is set.
    void run(const std::atomic<bool>& cancel, int threads);

    // Totals over the tiles done so far (read them once finished for the whole image).
    RayCounts rays() const;
    PrimaryStats primary_stats() const; // once finished
    std::uint64_t differing_pixels() const; // hybrid and ray primary hits name other objects
    double seconds() const;                 // since the job was made, to its last tile

  private:
    class PreviewSchedule;
    // The centres pass's pixels into the other views.
    void pixel(int x, int y, const Ray& ray, const PixelSample& sample) override;
    // Tile `index` of `pass` is traced: its bytes into that pass's image, then marked done.
    void show_tile(FramePass pass, int index, const RenderResult& result, const RayCounts& rays);
    // A pass's last tile is done: the next pass starts from a copy of its image.
    void pass_done(FramePass pass, const RenderResult& result);
    Image& image_of(FramePass pass);

    std::shared_ptr<const World> world_;
    std::shared_ptr<const IdImage> ids_;
    Resolve resolve_;
    bool compare_with_ray_;
    Image final_, normals_, difference_, reflections_;
    Image sampled_; // the final view after the grids
    Image spread_;  // and after adaptive's spreading
    std::vector<int> order_; // tile indices, nearest the image centre first
    int passes_ = 1;
    std::unique_ptr<std::atomic<int>[]> done_;
    std::vector<std::uint8_t> refined_map_; // once finished
    std::atomic<int> tiles_done_{0};
    std::atomic<bool> complete_{false};
    std::atomic<std::uint64_t> differing_{0};
    Stopwatch watch_; // from the job's making
    mutable std::mutex totals_mutex_;
    RayCounts rays_;
    PrimaryStats stats_;
    std::uint64_t refined_ = 0;
    double seconds_ = 0;
};

// Runs one job at a time, its frame on a thread of its own and its tiles on `threads` workers.
class Refiner {
  public:
    explicit Refiner(int threads);
    ~Refiner() { stop(); }
    Refiner(const Refiner&) = delete;
    Refiner& operator=(const Refiner&) = delete;

    // Stops the current job (if any) and starts tracing `job`.
    void start(std::shared_ptr<RefineJob> job);
    // Cancels the current job and waits for its workers: at most one tile each.
    void stop();
    int threads() const { return threads_; }

  private:
    int threads_;
    std::atomic<bool> cancel_{false};
    std::thread frame_;
    std::shared_ptr<RefineJob> job_;
};

} // namespace glint
