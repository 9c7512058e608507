#include "preview/preview.h"

#include "preview/orbit_camera.h"
#include "preview/refiner.h"
#include "preview/views.h"

#include "raster/item_buffer.h"
#include "raster/window.h"
#include "trace/image_metrics.h"
#include "trace/scene_loader.h"
#include "trace/stopwatch.h"

#include <glad/gl.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

namespace glint {

const std::string_view kPreviewKeys = R"(glint preview keys
  left drag         orbit around look_at
  right/middle drag pan
  wheel             dolly towards / away from look_at
  R                 reset the camera to the scene's
  1 … 6             view: final image, item buffer, depth, normals, ray vs hybrid, reflection depth
  V                 next view
  [ ]               max reflection depth − / +
  , .               reflection cut-off (min reflectivity) ÷2 / ×2
  - =               tessellation ÷2 / ×2 (mesh and auto raster modes)
  M                 raster mode: mesh / proxy / auto
  E                 resolve mode: exact / trust
  T                 tracer: hybrid (item buffer) / ray
  P                 save a screenshot PNG
  H                 this list
  Esc, Q            quit
)";

namespace {

using Clock = std::chrono::steady_clock; // for pacing frames; times are measured by Stopwatch

// Frame times of the UI thread: the work between two waits for input, not the wait.
struct FrameLog {
    double start_up = 0;                  // the first item buffer and trace start, milliseconds
    double first_frame = 0;               // the first image on screen
    std::vector<double> frames, restarts; // milliseconds
    double first_world = 0;               // preparing the scene at start-up, milliseconds
    std::vector<double> worlds;           // of each restart: the camera-relative world

    static double percentile(std::vector<double> v, double p) {
        if (v.empty()) return 0;
        std::sort(v.begin(), v.end());
        return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
    }
    void print() const {
        const auto over =
            std::count_if(frames.begin(), frames.end(), [](double t) { return t > 100; });
        std::printf("UI thread: start-up %.0f ms + first frame %.0f ms; then %zu frames, median "
                    "%.1f ms, 99th percentile %.1f "
                    "ms, max %.1f ms, "
                    "%td over 100 ms; %zu trace restarts (camera or setting changes), median %.1f "
                    "ms, max %.1f ms, of which the world median %.1f ms (at start-up %.1f ms)\n",
                    start_up, first_frame, frames.size(), percentile(frames, 0.5),
                    percentile(frames, 0.99), percentile(frames, 1.0), over, restarts.size(),
                    percentile(restarts, 0.5), percentile(restarts, 1.0), percentile(worlds, 0.5),
                    first_world);
    }
};

class Preview {
  public:
    explicit Preview(const PreviewOptions& options);
    ~Preview();
    Preview(const Preview&) = delete;
    Preview& operator=(const Preview&) = delete;

    int run();

  private:
    void restart();
    void show_base();
    bool upload_tiles(); // true when every tile of the current view is on screen
    void present();
    void save_screenshot(const std::filesystem::path& path);
    void update_title(bool force);
    std::string describe_settings() const;

    void on_key(int key);
    void on_cursor(double x, double y);
    void on_button(int button, int action);
    void on_scroll(double dy);

    const PreviewOptions& options_;
    Window window_;
    OrbitCamera camera_;
    Scene scene_;
    FrameSettings frame_;
    View view_ = View::final;
    ItemBuffer items_;
    bool upload_needed_ = true, dirty_ = true;
    // The camera the item buffer was drawn from: settings that leave it (depth, cut-off, resolve,
    // mode, views) reuse the item buffer; a new camera or upload draws it again.
    std::optional<Camera> drawn_camera_;
    std::shared_ptr<const IdImage> ids_;
    Image flat_, derived_; // derived_: the item-buffer or depth view, made when shown
    std::shared_ptr<RefineJob> job_;
    std::vector<char> uploaded_; // per tile of the current job, for the current view
    GLuint texture_ = 0, read_framebuffer_ = 0;
    int texture_width_ = 0, texture_height_ = 0;
    int button_ = -1; // the mouse button held, if any
    double cursor_x_ = 0, cursor_y_ = 0;
    bool screenshot_requested_ = false;
    int screenshots_ = 0;
    Stopwatch title_watch_;              // since the title last changed (restart() sets it first)
    std::shared_ptr<const World> world_; // of the current camera
    std::string title_;
    FrameLog log_;
    Refiner refiner_; // last: its workers stop before anything they read goes
};

Preview::Preview(const PreviewOptions& options)
    : options_(options),
      window_(options.scene.camera.width, options.scene.camera.height,
              ("glint preview — " + std::filesystem::path(options.scene_name).filename().string())
                  .c_str(),
              !options.scripted()),
      camera_(options.scene.camera), scene_(options.scene), frame_(options.frame),
      view_(options.view), refiner_(options.frame.threads) {
    glfwSwapInterval(0); // frames are paced by the loop; swapping never waits for a display
    glGenTextures(1, &texture_);
    glGenFramebuffers(1, &read_framebuffer_);
    GLFWwindow* w = window_.handle();
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, [](GLFWwindow* window, int key, int, int action, int) {
        if (action != GLFW_RELEASE)
            static_cast<Preview*>(glfwGetWindowUserPointer(window))->on_key(key);
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* window, double x, double y) {
        static_cast<Preview*>(glfwGetWindowUserPointer(window))->on_cursor(x, y);
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* window, int button, int action, int) {
        static_cast<Preview*>(glfwGetWindowUserPointer(window))->on_button(button, action);
    });
    glfwSetScrollCallback(w, [](GLFWwindow* window, double, double dy) {
        static_cast<Preview*>(glfwGetWindowUserPointer(window))->on_scroll(dy);
    });
}

Preview::~Preview() {
    refiner_.stop();
    glDeleteFramebuffers(1, &read_framebuffer_);
    glDeleteTextures(1, &texture_);
}

std::string Preview::describe_settings() const {
    std::string text(name_of(frame_.mode));
    if (frame_.mode == Mode::hybrid) {
        text.append(" ").append(name_of(frame_.raster));
        if (frame_.raster != RasterMode::proxy)
            text += " tess " + std::to_string(frame_.tessellation);
        text.append(" ").append(name_of(frame_.resolve));
    }
    const RenderSettings& render = scene_.render;
    text += ", depth " + std::to_string(render.max_depth);
    if (render.samples > 1)
        text += ", " + std::to_string(render.samples) + "x" + std::to_string(render.samples) + " " +
                std::string(name_of(render.antialias));
    return text;
}

void Preview::on_key(int key) {
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE);
        return;
    case GLFW_KEY_H:
        std::cout << kPreviewKeys << std::flush;
        return;
    case GLFW_KEY_P:
        screenshot_requested_ = true;
        return;
    case GLFW_KEY_R:
        camera_.reset();
        dirty_ = true;
        return;
    case GLFW_KEY_V:
        view_ = static_cast<View>((static_cast<int>(view_) + 1) % kViewCount);
        break;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET:
        scene_.render.max_depth = std::clamp(
            scene_.render.max_depth + (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1), 0, kMaxDepth);
        dirty_ = true;
        return;
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD: { // halving from 1e-4 reaches 0, doubling from 0 starts at 1e-4
        float& cutoff = scene_.render.min_reflectivity;
        cutoff = key == GLFW_KEY_PERIOD ? std::min(1.0f, std::max(cutoff * 2, 1e-4f))
                                        : (cutoff / 2 < 1e-4f ? 0.0f : cutoff / 2);
        dirty_ = true;
        return;
    }
    case GLFW_KEY_MINUS:
    case GLFW_KEY_EQUAL:
        frame_.tessellation =
            std::clamp(key == GLFW_KEY_EQUAL ? frame_.tessellation * 2 : frame_.tessellation / 2,
                       kMinTessellation, kMaxTessellation);
        upload_needed_ = dirty_ = true;
        return;
    case GLFW_KEY_M:
        frame_.raster = static_cast<RasterMode>((static_cast<int>(frame_.raster) + 1) %
                                                all_values<RasterMode>().size());
        upload_needed_ = dirty_ = true;
        return;
    case GLFW_KEY_E:
        frame_.resolve = frame_.resolve == Resolve::exact ? Resolve::trust : Resolve::exact;
        dirty_ = true;
        return;
    case GLFW_KEY_T:
        frame_.mode = frame_.mode == Mode::hybrid ? Mode::ray : Mode::hybrid;
        dirty_ = true;
        return;
    default:
        if (key < GLFW_KEY_1 || key >= GLFW_KEY_1 + kViewCount) return;
        view_ = static_cast<View>(key - GLFW_KEY_1);
    }
    // The difference view needs every camera ray cast beside the resolve: only traced for it.
    if (view_ == View::difference && frame_.mode == Mode::hybrid && job_ &&
        !job_->compares_with_ray())
        dirty_ = true;
    show_base(); // a new view
    update_title(true);
}

void Preview::on_button(int button, int action) {
    button_ = action == GLFW_PRESS ? button : -1;
    glfwGetCursorPos(window_.handle(), &cursor_x_, &cursor_y_);
}

void Preview::on_cursor(double x, double y) {
    const double dx = x - cursor_x_, dy = y - cursor_y_;
    cursor_x_ = x, cursor_y_ = y;
    if (button_ == GLFW_MOUSE_BUTTON_LEFT) {
        camera_.orbit(0.3 * dx, -0.3 * dy); // degrees per screen pixel
        dirty_ = true;
    } else if (button_ == GLFW_MOUSE_BUTTON_RIGHT || button_ == GLFW_MOUSE_BUTTON_MIDDLE) {
        // Cursor motion is in screen coordinates; the image is in framebuffer pixels.
        int window_width = 1, window_height = 1;
        glfwGetWindowSize(window_.handle(), &window_width, &window_height);
        const double scale =
            static_cast<double>(camera_.camera().width) / std::max(window_width, 1);
        camera_.pan(dx * scale, -dy * scale);
        dirty_ = true;
    }
}

void Preview::on_scroll(double dy) {
    camera_.dolly(dy);
    dirty_ = true;
}

// A new camera or setting: stop tracing, draw the item buffer (and the flat preview with it),
// show that, and start tracing tiles.
void Preview::restart() {
    const Stopwatch watch;
    refiner_.stop();
    job_.reset();
    Scene scene = scene_;
    scene.camera = camera_.camera();
    // The first world prepares the scene; later ones share its meshes and refit its structure.
    const Stopwatch world_watch;
    world_ = world_ ? std::make_shared<const World>(scene, *world_)
                    : std::make_shared<const World>(scene, options_.accel);
    log_.worlds.push_back(world_watch.milliseconds());
    const std::shared_ptr<const World>& world = world_;
    if (upload_needed_ || drawn_camera_ != scene.camera) {
        if (upload_needed_) items_.upload(*world, frame_.raster, frame_.tessellation);
        upload_needed_ = false;
        ItemBufferResult drawn = items_.draw(*world, true);
        bin_objects(*world, drawn.ids);
        flat_ = std::move(drawn.flat);
        ids_ = std::make_shared<const IdImage>(std::move(drawn.ids));
        drawn_camera_ = scene.camera;
    }
    job_ = std::make_shared<RefineJob>(world, frame_.mode == Mode::hybrid ? ids_ : nullptr,
                                       frame_.resolve, view_ == View::difference);
    refiner_.start(job_);
    show_base();
    dirty_ = false;
    log_.restarts.push_back(watch.milliseconds());
    update_title(true);
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
                     is_traced(view_) ? 0 : job_->passes());
}

bool Preview::upload_tiles() {
    if (!job_) return true;
    if (!is_traced(view_)) return true;
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

// The title is the overlay: view, settings, progress and timings. Set only when its text changes:
// each change is an X event that would wake the idle loop again.
void Preview::update_title(bool force) {
    if (!force && title_watch_.milliseconds() < 250) return;
    title_watch_.restart();
    std::string title = "glint preview — " +
                        std::filesystem::path(options_.scene_name).filename().string() + " — " +
                        std::string(view_label(view_)) + " — " + describe_settings() + " — ";
    if (job_) {
        char progress[160];
        const RayCounts rays = job_->rays();
        if (job_->finished())
            std::snprintf(progress, sizeof progress, "%dx%d traced in %.2f s, %.2f M rays",
                          job_->width(), job_->height(), job_->seconds(),
                          static_cast<double>(rays.total()) / 1e6);
        else
            std::snprintf(progress, sizeof progress, "%dx%d %s %d%%", job_->width(), job_->height(),
                          job_->tiles_done() < job_->tile_count() ? "tracing" : "refining",
                          100 * job_->tiles_done() / (job_->passes() * job_->tile_count()));
        title += progress;
        if (view_ == View::difference)
            title += ", " + std::to_string(job_->differing_pixels()) + " pixels differ";
    }
    title += " — H: keys";
    if (title == title_) return;
    title_ = title;
    glfwSetWindowTitle(window_.handle(), title_.c_str());
}

// The event loop (65 lines, one body so that pacing, restarts, uploads and the frame log read in
// the order they happen each frame).
int Preview::run() {
    GLFWwindow* w = window_.handle();
    if (!options_.scripted()) std::cout << kPreviewKeys << std::flush;
    // The first item buffer compiles llvmpipe's shader variants and touches every buffer for the
    // first time: start-up, reported apart from the frames.
    const Stopwatch start_up;
    restart();
    log_.start_up = start_up.milliseconds();
    log_.restarts.clear();
    log_.first_world = log_.worlds.front();
    log_.worlds.clear();
    const auto period = std::chrono::microseconds(16667); // at most 60 frames a second
    auto next_frame = Clock::now();
    int frames = 0;
    bool complete = false;
    while (!glfwWindowShouldClose(w)) {
        // Wait for input; while something is still to show, no longer than the next frame.
        if (options_.scripted() || dirty_ || !complete)
            glfwWaitEventsTimeout(
                std::max(0.0, std::chrono::duration<double>(next_frame - Clock::now()).count()));
        else
            glfwWaitEvents();
        const Stopwatch frame_watch;
        next_frame = Clock::now() + period;
        if (frames >= 1 && static_cast<std::size_t>(frames - 1) < options_.keys.size()) {
            const char key = options_.keys[static_cast<std::size_t>(frames - 1)];
            on_key(std::toupper(static_cast<unsigned char>(key))); // GLFW's codes are ASCII
        }
        if (options_.spin != 0 && frames < options_.frames) {
            camera_.orbit(options_.spin, 0);
            dirty_ = true;
        }
        const auto [width, height] = window_.framebuffer_size();
        if (width > 0 && height > 0 &&
            (width != camera_.camera().width || height != camera_.camera().height)) {
            camera_.resize(width, height);
            dirty_ = true;
        }
        if (dirty_ && width > 0 && height > 0) restart();
        complete = upload_tiles() && job_ && job_->finished();
        present();
        ++frames;
        const bool done = options_.scripted() && frames >= options_.frames &&
                          static_cast<std::size_t>(frames) > options_.keys.size() && complete;
        // The first frame puts the first image on screen: part of start-up.
        (frames == 1 ? log_.first_frame : log_.frames.emplace_back()) = frame_watch.milliseconds();
        update_title(complete);
        if (screenshot_requested_ || (done && !options_.screenshot.empty())) {
            std::filesystem::path path = options_.screenshot;
            if (screenshot_requested_ || path.empty()) {
                std::filesystem::create_directories("out");
                path = "out/" + std::filesystem::path(options_.scene_name).stem().string() +
                       "-preview-" + std::to_string(++screenshots_) + ".png";
            }
            try {
                save_screenshot(path);
            } catch (const std::exception& e) {
                if (done) throw; // scripted: the screenshot was the point
                std::cerr << "glint: error: could not save a screenshot: " << e.what() << "\n";
            }
            screenshot_requested_ = false;
        }
        glfwSwapBuffers(w);
        if (done) break;
    }
    log_.print();
    std::printf("item buffers drawn: %zu\n", items_.draws());
    if (job_ && job_->finished())
        std::printf("last trace: %dx%d in %.2f s on %d threads\n", job_->width(), job_->height(),
                    job_->seconds(), refiner_.threads());
    return 0;
}

} // namespace

int run_preview(const PreviewOptions& options) {
    Preview preview(options);
    return preview.run();
}

} // namespace glint
