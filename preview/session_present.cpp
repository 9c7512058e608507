// Putting the trace on screen (preview/session.h): a restart draws the item buffer and starts
// the refiner, its tiles go into a texture as they finish, and the texture onto the window.
#include "preview/session.h"

#include "io/png.h"
#include "trace/stopwatch.h"

#include <algorithm>
#include <cstdio>

namespace glint {

// A new camera or setting: stop tracing, draw the item buffer (and the flat preview with it),
// show that, and start tracing tiles.
void Preview::restart() {
    const Stopwatch watch;
    refiner_.stop();
    job_.reset();
    retire_comparison(); // of the last camera and settings
    Scene scene = scene_;
    scene.camera = camera_.camera();
    // The first world prepares the scene; later ones share its meshes and refit its structure.
    const Stopwatch world_watch;
    world_ = world_            ? std::make_shared<const World>(scene, *world_)
             : posed_geometry_ ? std::make_shared<const World>(scene, posed_geometry_, accel_)
                               : std::make_shared<const World>(scene, accel_);
    log_.worlds.push_back(world_watch.milliseconds());
    const std::shared_ptr<const World>& world = world_;
    // An explained pixel is explained again for new settings; a new camera forgets it.
    if (explained_ && drawn_camera_ == scene.camera && !explain_pending_)
        explain_pending_ = explained_;
    if (drawn_camera_ != scene.camera) explained_.reset(), overlay_.clear(), explanation_.clear();
    if (upload_needed_ || drawn_camera_ != scene.camera) {
        const Stopwatch items_watch;
        if (upload_needed_) items_.upload(*world, frame_.raster, frame_.tessellation);
        upload_needed_ = false;
        ItemBufferResult drawn = items_.draw(*world, true);
        item_buffer_ms_ = items_watch.milliseconds();
        bin_objects(*world, drawn.ids);
        flat_ = std::move(drawn.flat);
        ids_ = std::make_shared<const IdImage>(std::move(drawn.ids));
        drawn_camera_ = scene.camera;
    }
    job_ = std::make_shared<RefineJob>(world, frame_.mode == Mode::hybrid ? ids_ : nullptr,
                                       frame_.resolve, view_ == View::difference && !reference_);
    refiner_.start(job_);
    show_base();
    dirty_ = false;
    log_.restarts.push_back(watch.milliseconds());
}

// Puts the current view's whole image in the texture: the item buffer's own views, or the flat
// preview that traced tiles then replace as they finish.
void Preview::show_base() {
    if (!job_) return;
    const int width = job_->width(), height = job_->height();
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    const Image* base = &flat_;
    if (view_ == View::items)
        derived_ = false_colour(ids_->ids, ids_->width, ids_->height), base = &derived_;
    if (view_ == View::depth) derived_ = depth_image(*ids_), base = &derived_;
    if (const Image* compared = compared_view())
        base = compared; // else the flat image, until ready
    if (width != texture_width_ || height != texture_height_) {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE,
                     base->rgb.data());
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffer_);
        glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_,
                               0);
        texture_width_ = width, texture_height_ = height;
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE,
                        base->rgb.data());
    }
    // Per tile, how many of the job's passes the texture shows (all, for an untraced view).
    uploaded_.assign(static_cast<std::size_t>(job_->tile_count()),
                     from_refiner() ? 0 : job_->passes());
}

bool Preview::upload_tiles() {
    if (!job_) return true;
    if (!from_refiner()) return true;
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, job_->width());
    bool all = true;
    for (int t = 0; t < job_->tile_count(); ++t) {
        // Only the final image changes in the second pass (the sample grids).
        const int wanted = view_ == View::final ? job_->passes() : 1;
        const int passes = std::min(job_->tile_passes(t), wanted);
        if (uploaded_[static_cast<std::size_t>(t)] >= wanted) continue;
        if (passes <= uploaded_[static_cast<std::size_t>(t)]) {
            all = false;
            continue;
        }
        const TileRect r = job_->tile(t);
        const Image& image = job_->traced(view_, passes);
        glPixelStorei(GL_UNPACK_SKIP_PIXELS, r.x0);
        glPixelStorei(GL_UNPACK_SKIP_ROWS, r.y0);
        glTexSubImage2D(GL_TEXTURE_2D, 0, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0, GL_RGB,
                        GL_UNSIGNED_BYTE, image.rgb.data());
        uploaded_[static_cast<std::size_t>(t)] = passes;
        all &= passes == wanted;
    }
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
    return all;
}

// The texture (row 0 = the image's top) onto the window, flipped to GL's bottom-up rows, scaled
// to the framebuffer while a resize is on its way.
void Preview::present() {
    const auto [width, height] = window_.framebuffer_size();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    if (texture_width_ > 0) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffer_);
        glBlitFramebuffer(0, 0, texture_width_, texture_height_, 0, height, width, 0,
                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    panel_->begin_frame();
    if (panel_visible_) {
        draw_overlay();
        draw_panel();
    }
    panel_->end_frame();
}

// The window's framebuffer as shown (call after present(), before swapping).
void Preview::save_screenshot(const std::filesystem::path& path) {
    const auto [width, height] = window_.framebuffer_size();
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    Image image(width, height);
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    for (int y = 0; y < height; ++y)
        std::copy_n(&rgb[static_cast<std::size_t>(height - 1 - y) * row], row,
                    &image.rgb[static_cast<std::size_t>(y) * row]);
    write_png(path, image);
    std::printf("glint: saved %s (%dx%d, %s)\n", path.c_str(), width, height,
                std::string(view_label(view_)).c_str());
}

} // namespace glint
