// The preview's comparison of its live setting against a reference (docs/PREVIEW.md, "Against a
// reference"): both sides traced on a thread of its own once the live trace has finished, then
// the difference (frame/difference.h), its heat and cause maps, the differing pixels' view, and
// a clicked pixel's two trees (frame/explain_against.h). No GL is made on that thread: a hybrid
// side's item buffer is drawn by the window beforehand.
#pragma once

#include "frame/difference.h"
#include "trace/image.h"

#include <atomic>
#include <memory>
#include <string>
#include <thread>

namespace glint {

class ReferenceComparison {
  public:
    struct Input {
        Side live;
        std::shared_ptr<const World> live_world;      // of live.scene, as the window traces it
        std::shared_ptr<const IdImage> live_ids;      // hybrid: the window's item buffer
        Side reference;                               // its scene: the live one with its settings
        std::shared_ptr<const IdImage> reference_ids; // hybrid: drawn for its raster and tess
    };

    // Starts the comparison on a thread of its own.
    explicit ReferenceComparison(Input input);
    // Waits for the thread (a comparison no longer wanted is kept until it is done: see
    // ready()).
    ~ReferenceComparison();
    ReferenceComparison(const ReferenceComparison&) = delete;
    ReferenceComparison& operator=(const ReferenceComparison&) = delete;

    bool ready() const { return ready_.load(std::memory_order_acquire); }
    // Once ready: what went wrong, or empty.
    const std::string& error() const { return error_; }
    // Once ready without error:
    const FrameDifference& difference() const { return difference_; }
    // The maps at the frame's size, their legends left to the panel.
    const Image& heat() const { return heat_; }
    const Image& causes() const { return causes_; }
    // The live image darkened, its differing pixels red (preview/views.h's difference colour).
    const Image& differing() const { return differing_; }
    // The two trees of pixel (x, y) side by side, as `glint explain --against` prints them.
    std::string explain(int x, int y, const std::string& scene_name) const;

  private:
    void run();

    Input input_;
    std::unique_ptr<RenderedSide> live_, reference_;
    FrameDifference difference_;
    Image heat_, causes_, differing_;
    std::string error_;
    std::atomic<bool> ready_{false};
    std::thread thread_; // last: it starts once the rest is made
};

} // namespace glint
