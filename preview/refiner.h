// Progressive tracing for the preview: one job per camera and settings, traced in 32×32 tiles
// from the image centre outwards by worker threads, while the UI thread shows each tile as it
// finishes. A job is cancelled (between tiles) as soon as the camera moves. Each traced pixel is
// computed exactly as `glint render` computes it, so a finished job is the headless image.
// With the scene's samples N > 1, a second pass follows the first (one sample a pixel, from the
// same item buffer): every pixel's N×N grid, or with adaptive antialiasing the pixels the rule
// refines from the first pass (trace/sampling.h), the samples' primary hits cast as rays; with
// adaptive, a third pass (one worker) spreads the refinement as the rule's last part says.
#pragma once

#include "preview/views.h"

#include "trace/render.h"
#include "trace/stopwatch.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

class RefineJob {
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
    // read a tile's pixels only once tile_passes says that many are done. Only the final view
    // changes in the second pass, which writes a copy of the first's image, so a tile shown
    // after the first pass is never written again.
    const Image& traced(View view, int passes = 3) const;
    int tile_count() const { return static_cast<int>(order_.size()); } // per pass
    TileRect tile(int index) const;                                    // in row-major tile order
    int passes() const { return passes_; }
    // How many passes have finished tile `index` (0 … passes()).
    int tile_passes(int index) const { return done_[index].load(std::memory_order_acquire); }
    bool tile_done(int index) const { return tile_passes(index) > 0; }
    int tiles_done() const { return tiles_done_.load(std::memory_order_acquire); } // all passes
    bool finished() const { return tiles_done() == passes_ * tile_count(); }
    // Pixels the second pass refines (all with uniform antialiasing); 0 before it starts.
    std::uint64_t refined_pixels() const;
    // Whether pixel (x, y) took its grid (adaptive antialiasing, all passes); read once finished.
    bool refined(int x, int y) const {
        return !refine_.empty() && refine_[static_cast<std::size_t>(y) * width() + x] != 0;
    }

    // Traces tiles until none is left or `cancel` is set; several threads may call it at once.
    void work(const std::atomic<bool>& cancel);

    // Totals over the tiles done so far (read them once finished for the whole image).
    RayCounts rays() const;
    PrimaryStats primary_stats() const;
    std::uint64_t differing_pixels() const; // hybrid and ray primary hits name other objects
    double seconds() const;                 // since the job was made, to its last tile

  private:
    void trace_tile(const TileRect& rect);
    void refine_tile(const TileRect& rect);
    // After the first pass's last tile: which pixels the second pass refines.
    void plan_refinement();
    void spread(const std::atomic<bool>& cancel);
    RayCounts grid_into(Image& image, int x, int y, std::vector<Hit>& hits) const;
    // Until the first pass is done and planned; false if cancelled first.
    bool wait_for_first_pass(const std::atomic<bool>& cancel);

    std::shared_ptr<const World> world_;
    std::shared_ptr<const IdImage> ids_;
    Resolve resolve_;
    bool compare_with_ray_;
    Image final_, normals_, difference_, reflections_;
    Image sampled_; // the final view after the second pass
    Image spread_;  // and after adaptive's spreading (the third)
    std::vector<int> order_; // tile indices, nearest the image centre first
    int passes_ = 1;
    std::unique_ptr<std::atomic<int>[]> done_;
    std::vector<std::uint64_t> path_keys_; // first pass, for adaptive antialiasing
    std::vector<std::uint8_t> refine_;     // the second pass's pixels
    std::atomic<bool> planned_{false};
    std::uint64_t refined_ = 0;
    std::atomic<int> next_{0}, tiles_done_{0};
    Stopwatch watch_; // from the job's making
    mutable std::mutex totals_mutex_;
    RayCounts rays_;
    PrimaryStats stats_;
    std::uint64_t differing_ = 0;
    double seconds_ = 0;
};

// Runs one job at a time on `threads` worker threads.
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
    std::vector<std::thread> workers_;
    std::shared_ptr<RefineJob> job_;
};

} // namespace glint
