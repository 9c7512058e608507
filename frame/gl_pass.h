// Hybrid mode's GL pass on a thread of its own (docs/ITEM_BUFFER.md, "How a hybrid frame is
// made"): the GL context and the shaders are made as soon as the pass starts, which needs
// nothing from the scene, while the caller builds the World; once handed the World, the thread
// uploads, draws and reads back the item buffers and bins them for the resolve. The World does
// not depend on the raster, nor the raster on the World's structures, so the two run side by
// side and the frame's tracing starts when both are ready. The context is made, used and
// destroyed on that one thread (GL contexts are current per thread), and its teardown runs
// beside the tracing. A sequence (`glint render --frames N`) hands it one World a frame: the
// context and shaders are made once, and each frame uploads and draws its own.
#pragma once

#include "frame/frame_settings.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace glint {

// Whether a frame of `world` with `settings` draws an item buffer: hybrid mode and an object to
// draw (ray mode and an empty scene get no GL context).
bool needs_gl(const FrameSettings& settings, std::size_t objects);

class GlPass {
  public:
    // Starts the thread: GL context, then shaders (settings.gl names the back end).
    explicit GlPass(const FrameSettings& settings);
    // Joins the thread; a pass never handed a World stops after its shaders.
    ~GlPass();
    GlPass(const GlPass&) = delete;
    GlPass& operator=(const GlPass&) = delete;

    // Hands the World over (it must outlive finish()): the thread draws its item buffers. After
    // finish(), the next frame's World may be handed over the same way.
    void draw(const World& world);
    // Waits for the pass and moves what it made into `frame` (items, sample_items, deviations,
    // proxies, tessellated, gl_renderer, and the times of context, compile, upload, raster and
    // the bins, as primary; and as times.overlapped, the part of them that ran before this
    // call, beside the caller's work). Context and compile are the first frame's: later frames
    // reuse them and count 0. Rethrows what the thread threw: GlError when there is no usable GL.
    void finish(Frame& frame);

  private:
    void run();
    // Draws `world`'s item buffers into made_ with the pass's item buffer.
    void draw_frame(const World& world, class ItemBuffer& items);

    FrameSettings settings_;
    std::mutex mutex_;
    std::condition_variable changed_;
    const World* world_ = nullptr; // handed and not yet drawn
    bool stopping_ = false;        // the destructor: no further World comes
    bool done_ = false;            // made_ (or error_) holds the frame handed last
    std::exception_ptr error_;
    bool handed_ = false;
    Frame made_; // written by the thread until done_, then read by finish()
    std::thread thread_;
};

} // namespace glint
