// `glint preview`'s event loop (preview/session.h: the window's state, its other members by job).
#include "preview/preview.h"

#include "frame/explain.h"
#include "preview/session.h"
#include "preview/settings.h"
#include "trace/stopwatch.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace glint {

namespace {
using Clock = std::chrono::steady_clock; // for pacing frames; times are measured by Stopwatch
} // namespace

Preview::Preview(const PreviewOptions& options)
    : options_(options),
      window_(options.scene.camera.width, options.scene.camera.height,
              ("glint preview — " + std::filesystem::path(options.scene_name).filename().string())
                  .c_str(),
              !options.scripted()),
      camera_(options.scene.camera), scene_(options.scene), frame_(options.frame),
      view_(options.view), accel_(options.accel), panel_visible_(options.panel),
      refiner_(options.frame.threads) {
    time_ = options.time;
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
    panel_.emplace(w);
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
    char cutoff[48];
    std::snprintf(cutoff, sizeof cutoff, ", cut-off %g",
                  static_cast<double>(render.min_reflectivity));
    text += cutoff;
    text += ", " + (world_   ? std::string(name_of(world_->accelerator().kind()))
                    : accel_ ? std::string(name_of(*accel_))
                             : std::string("auto"));
    text += ", view " + std::string(name_of(view_));
    if (reference_) text += ", against " + reference_->label;
    return text;
}

bool Preview::compares() const {
    return reference_.has_value() || view_ == View::heat || view_ == View::causes;
}

bool Preview::from_refiner() const {
    return is_traced(view_) && !(reference_ && view_ == View::difference);
}

const Image* Preview::compared_view() const {
    if (!comparison_ || !comparison_->ready() || !comparison_->error().empty()) return nullptr;
    if (view_ == View::heat) return &comparison_->heat();
    if (view_ == View::causes) return &comparison_->causes();
    if (view_ == View::difference && reference_) return &comparison_->differing();
    return nullptr;
}

void Preview::retire_comparison() {
    if (comparison_ && !comparison_->ready()) retired_.push_back(std::move(comparison_));
    comparison_.reset();
    comparison_shown_ = false;
}

// The live scene as the window traces it, and the reference on the same camera: exact (depth
// kMaxDepth, no cut-off, double; the live sampling), or the settings taken. A hybrid reference
// gets its item buffer here, from the window's GL.
void Preview::start_comparison() {
    retire_comparison();
    Scene scene = scene_;
    scene.camera = camera_.camera();
    Side live{"the view's settings", scene, accel_, frame_};
    Side reference;
    if (reference_choice_ == "taken") {
        reference = *reference_;
        reference.scene.camera = scene.camera;
    } else { // exact, chosen or the maps' default, with the live scene's sampling
        reference.label = "exact";
        reference.scene = scene;
        make_exact(reference);
    }
    std::shared_ptr<const IdImage> reference_ids;
    if (reference.frame.mode == Mode::hybrid) {
        const auto drawn_as = std::pair{reference.frame.raster, reference.frame.tessellation};
        if (drawn_as == std::pair{frame_.raster, frame_.tessellation}) {
            reference_ids = ids_;
        } else {
            if (reference_uploaded_ != drawn_as)
                reference_items_.upload(*world_, drawn_as.first, drawn_as.second);
            reference_uploaded_ = drawn_as;
            ItemBufferResult drawn = reference_items_.draw(*world_);
            bin_objects(*world_, drawn.ids);
            reference_ids = std::make_shared<const IdImage>(std::move(drawn.ids));
        }
    }
    comparison_ = std::make_shared<ReferenceComparison>(ReferenceComparison::Input{
        std::move(live), world_, frame_.mode == Mode::hybrid ? ids_ : nullptr, std::move(reference),
        std::move(reference_ids)});
}

void Preview::set(const std::string& name, const std::string& value) {
    switch (set_panel_setting(
        {frame_, scene_.render, accel_, view_, panel_visible_, reference_choice_, time_}, name,
        value)) {
    case Effect::new_world:
        world_.reset(); // a structure of another kind: built afresh, not refitted
        dirty_ = true;
        break;
    case Effect::upload:
        upload_needed_ = dirty_ = true;
        break;
    case Effect::retrace:
        dirty_ = true;
        break;
    case Effect::view:
        if (view_ == View::difference && !reference_ && frame_.mode == Mode::hybrid && job_ &&
            !job_->compares_with_ray())
            dirty_ = true;
        show_base();
        break;
    case Effect::panel:
        break;
    case Effect::pose:
        pose();
        break;
    case Effect::reference:
        if (reference_choice_ == "none") {
            reference_.reset();
        } else if (reference_choice_ == "exact") {
            reference_ = Side{"exact", scene_, std::nullopt, FrameSettings{}};
            make_exact(*reference_);
        } else { // taken: the settings as they are now
            reference_ = Side{"", scene_, accel_, frame_};
            reference_->label = "taken: " + describe_side(*reference_);
        }
        retire_comparison();
        show_base();
        break;
    }
    std::printf("glint: panel: %s = %s\n", name.c_str(), value.c_str());
    std::fflush(stdout);
}

void Preview::pose() {
    if (!scene_.animation) return;
    scene_.animation->pose(scene_, time_);
    const std::shared_ptr<const SceneGeometry> before =
        posed_geometry_ ? posed_geometry_ : world_ ? world_->geometry() : nullptr;
    posed_geometry_ = before ? SceneGeometry::posed(before, scene_) : nullptr;
    world_.reset(); // the objects moved: the top level is built afresh over the posed geometry
    upload_needed_ = dirty_ = true;
}

void Preview::explain(int x, int y) {
    const PrimarySource source{frame_.mode == Mode::hybrid ? ids_.get() : nullptr, frame_.resolve};
    const int n = world_->settings().samples;
    const PixelExplanation e =
        explain_pixel(*world_, source, x, y, n / 2, n / 2, job_->refined(x, y));
    Scene scene = scene_;
    scene.camera = camera_.camera();
    const std::string what = std::filesystem::path(options_.scene_name).filename().string() + " (" +
                             std::to_string(scene.camera.width) + "x" +
                             std::to_string(scene.camera.height) + "), preview, " +
                             describe_settings();
    explanation_ = explanation_text(scene, *world_, e, what);
    // In a view of the comparison, the pixel's two trees (`glint explain --against`).
    if (compared_view())
        explanation_ =
            comparison_->explain(x, y, std::filesystem::path(options_.scene_name).filename());
    overlay_ = tree_segments(*world_, e);
    explained_ = std::pair{x, y};
    std::fputs(explanation_.c_str(), stdout);
    std::fflush(stdout);
}

// The event loop, one body so that pacing, restarts, uploads and the frame log read in the
// order they happen each frame.
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
    auto played_at = Clock::now(); // when an animation playing was last advanced
    while (!glfwWindowShouldClose(w)) {
        // Wait for input; while something is still to show (a trace or a comparison under way),
        // no longer than the next frame.
        if (options_.scripted() || dirty_ || !complete || playing_)
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
        if (frames == 1)
            for (const std::string& assignment : options_.settings) {
                const auto [name, value] = split_assignment(assignment);
                set(name, value);
            }
        if (playing_ && scene_.animation) {
            // Played at the wall clock's pace, from where the slider left it, round and round.
            const auto now = Clock::now();
            const double duration = std::max(scene_.animation->duration(), 1e-3);
            time_ = std::fmod(time_ + std::chrono::duration<double>(now - played_at).count(), duration);
            played_at = now;
            pose();
        } else {
            played_at = Clock::now();
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
        std::erase_if(retired_, [](const auto& c) { return c->ready(); });
        if (complete && compares() && !comparison_) start_comparison();
        if (comparison_ && comparison_->ready() && !comparison_shown_) {
            if (!comparison_->error().empty())
                std::cerr << "glint: error: the comparison failed: " << comparison_->error()
                          << "\n";
            comparison_shown_ = true;
            show_base();
        }
        complete = complete && (!compares() || (comparison_ && comparison_->ready()));
        if (frames == 0 && options_.click) explain_pending_ = options_.click; // once, when traced
        if (complete && explain_pending_) {
            explain(explain_pending_->first, explain_pending_->second);
            explain_pending_.reset();
        }
        present();
        ++frames;
        const bool done = options_.scripted() && frames >= options_.frames &&
                          static_cast<std::size_t>(frames) > options_.keys.size() && complete &&
                          !explain_pending_;
        // The first frame puts the first image on screen: part of start-up.
        (frames == 1 ? log_.first_frame : log_.frames.emplace_back()) = frame_watch.milliseconds();
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
    std::printf("settings: %s\n", describe_settings().c_str());
    if (job_ && job_->finished())
        std::printf("last trace: %dx%d in %.2f s on %d threads\n", job_->width(), job_->height(),
                    job_->seconds(), refiner_.threads());
    return 0;
}

int run_preview(const PreviewOptions& options) {
    Preview preview(options);
    return preview.run();
}

} // namespace glint
