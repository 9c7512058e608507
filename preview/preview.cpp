#include "preview/preview.h"

#include "preview/orbit_camera.h"
#include "preview/panel.h"
#include "preview/ray_overlay.h"
#include "preview/refiner.h"
#include "preview/views.h"

#include "frame/explain.h"

#include "io/error.h"
#include "io/png.h"
#include "preview/window.h"
#include "raster/item_buffer.h"
#include "trace/image_metrics.h"
#include "trace/stopwatch.h"

#include <glad/gl.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <stdexcept>

namespace glint {

const std::string_view kPreviewKeys = R"(glint preview keys
  left drag         orbit around look_at
  right/middle drag pan
  wheel             dolly towards / away from look_at
  left click        explain the pixel: its ray tree drawn, the explanation in the panel
  G                 the panel (and the explained tree) on / off
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

const std::vector<std::string> kPreviewSettings = {"mode",   "raster", "resolve", "depth",
                                                   "cutoff", "tess",   "samples", "aa",
                                                   "accel",  "view",   "panel"};

namespace {

// What the panel controls, wherever it lives (the preview's members, or a scratch copy when a
// scripted --set is checked).
struct PanelState {
    FrameSettings& frame;
    RenderSettings& render;
    std::optional<AccelKind>& accel;
    View& view;
    bool& panel;
};

// What a change of setting asks of the preview.
enum class Effect { retrace, upload, new_world, view, panel };

std::string one_of(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
    return text;
}

template <class Enum> Enum parse_name(const std::string& name, const std::string& value) {
    if (const std::optional<Enum> v = from_name<Enum>(value)) return *v;
    throw std::invalid_argument(name + "=" + value + ": expected one of " +
                                one_of(all_names<Enum>()));
}

double parse_number(const std::string& name, const std::string& value, double lo, double hi) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != value.size() || !(v >= lo && v <= hi))
        throw std::invalid_argument(name + "=" + value + ": expected a number from " +
                                    std::to_string(lo).substr(0, std::to_string(lo).find('.')) +
                                    " to " +
                                    std::to_string(hi).substr(0, std::to_string(hi).find('.')));
    return v;
}

int parse_whole(const std::string& name, const std::string& value, int lo, int hi) {
    const double v = parse_number(name, value, lo, hi);
    if (v != static_cast<int>(v))
        throw std::invalid_argument(name + "=" + value + ": expected a whole number");
    return static_cast<int>(v);
}

// Sets one of the panel's settings by name: the panel's controls and --set both come here.
Effect set_panel_setting(const PanelState& s, const std::string& name, const std::string& value) {
    if (name == "mode") return s.frame.mode = parse_name<Mode>(name, value), Effect::retrace;
    if (name == "raster")
        return s.frame.raster = parse_name<RasterMode>(name, value), Effect::upload;
    if (name == "resolve")
        return s.frame.resolve = parse_name<Resolve>(name, value), Effect::retrace;
    if (name == "depth")
        return s.render.max_depth = parse_whole(name, value, 0, kMaxDepth), Effect::retrace;
    if (name == "cutoff")
        return s.render.min_reflectivity = static_cast<float>(parse_number(name, value, 0, 1)),
               Effect::retrace;
    if (name == "tess")
        return s.frame.tessellation = parse_whole(name, value, kMinTessellation, kMaxTessellation),
               Effect::upload;
    if (name == "samples")
        return s.render.samples = parse_whole(name, value, 1, kMaxSamples), Effect::retrace;
    if (name == "aa")
        return s.render.antialias = parse_name<Antialias>(name, value), Effect::retrace;
    if (name == "accel") {
        s.accel = value == "auto" ? std::nullopt
                                  : std::optional<AccelKind>(parse_name<AccelKind>(name, value));
        return Effect::new_world;
    }
    if (name == "view") return s.view = parse_name<View>(name, value), Effect::view;
    if (name == "panel") {
        if (value != "on" && value != "off")
            throw std::invalid_argument(name + "=" + value + ": expected on or off");
        return s.panel = value == "on", Effect::panel;
    }
    throw std::invalid_argument("no setting named '" + name +
                                "' (the panel's: " + one_of(kPreviewSettings) + ")");
}

std::pair<std::string, std::string> split_assignment(const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos)
        throw std::invalid_argument(
            assignment + ": expected name=value (names: " + one_of(kPreviewSettings) + ")");
    return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

} // namespace

PanelPlace panel_place(float window_width, float window_height) {
    const float width = std::min(360.0f, window_width * 0.45f);
    return {window_width - width - 6, 6, width, window_height - 12};
}

void check_preview_setting(const std::string& assignment) {
    FrameSettings frame;
    RenderSettings render;
    std::optional<AccelKind> accel;
    View view = View::final;
    bool panel = true;
    const auto [name, value] = split_assignment(assignment);
    set_panel_setting({frame, render, accel, view, panel}, name, value);
}

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
    std::string describe_settings() const;

    void on_key(int key);
    void on_cursor(double x, double y);
    void on_button(int button, int action);
    void on_scroll(double dy);

    // The panel's path for every setting (its controls, and scripted --set).
    void set(const std::string& name, const std::string& value);
    // Explains pixel (x, y) of the finished trace: the text to stdout and the panel, the tree's
    // segments to the overlay.
    void explain(int x, int y);
    void draw_panel();
    void draw_overlay();
    // The image pixel under window position (x, y), if any.
    std::optional<std::pair<int, int>> pixel_at(double x, double y) const;

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
    double press_x_ = 0, press_y_ = 0; // where the left button went down
    bool dragged_ = false;             // since then, moved far enough to orbit (not a click)
    std::optional<AccelKind> accel_;
    bool panel_visible_ = true;
    // The explained pixel, its text and its tree's segments; explained again after a setting
    // changes (once the new trace finishes), forgotten when the camera moves.
    std::optional<std::pair<int, int>> explained_, explain_pending_;
    std::string explanation_;
    std::vector<OverlaySegment> overlay_;
    double item_buffer_ms_ = 0;
    bool screenshot_requested_ = false;
    int screenshots_ = 0;
    std::shared_ptr<const World> world_; // of the current camera
    FrameLog log_;
    // After the window: ImGui's callbacks chain to the preview's, set before it, and it is gone
    // before the window's GL context.
    std::optional<Panel> panel_;
    Refiner refiner_; // last: its workers stop before anything they read goes
};

Preview::Preview(const PreviewOptions& options)
    : options_(options),
      window_(options.scene.camera.width, options.scene.camera.height,
              ("glint preview — " + std::filesystem::path(options.scene_name).filename().string())
                  .c_str(),
              !options.scripted()),
      camera_(options.scene.camera), scene_(options.scene), frame_(options.frame),
      view_(options.view), accel_(options.accel), panel_visible_(options.panel),
      refiner_(options.frame.threads) {
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
    return text + ", view " + std::string(name_of(view_));
}

namespace {

// One colour per ray kind (docs/PREVIEW.md), as ImGui packs them (ABGR).
ImU32 overlay_colour(OverlaySegment::Kind kind) {
    switch (kind) {
    case OverlaySegment::Kind::primary:
        return IM_COL32(255, 255, 255, 255);
    case OverlaySegment::Kind::reflection:
        return IM_COL32(60, 220, 255, 255);
    case OverlaySegment::Kind::transmission:
        return IM_COL32(120, 255, 120, 255);
    case OverlaySegment::Kind::shadow:
        return IM_COL32(255, 220, 60, 255);
    case OverlaySegment::Kind::blocked_shadow:
        break;
    }
    return IM_COL32(255, 70, 70, 255);
}

// A combo box over an enum's names; returns the chosen name when it changes.
template <class Enum> std::optional<std::string> enum_combo(const char* label, Enum value) {
    std::optional<std::string> chosen;
    if (ImGui::BeginCombo(label, std::string(name_of(value)).c_str())) {
        for (const Enum v : all_values<Enum>())
            if (ImGui::Selectable(std::string(name_of(v)).c_str(), v == value))
                chosen = std::string(name_of(v));
        ImGui::EndCombo();
    }
    return chosen;
}

} // namespace

// The tree's segments over the image, scaled from image pixels to the window: blocked shadow
// rays dashed, the primary ray a ring around the clicked pixel.
void Preview::draw_overlay() {
    if (overlay_.empty() || !job_) return;
    ImDrawList* draw = panel_->background();
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const float sx = size.x / static_cast<float>(job_->width());
    const float sy = size.y / static_cast<float>(job_->height());
    for (const OverlaySegment& s : overlay_) {
        const ImVec2 a(s.x0 * sx, s.y0 * sy), b(s.x1 * sx, s.y1 * sy);
        const ImU32 colour = overlay_colour(s.kind);
        if (s.kind == OverlaySegment::Kind::primary) {
            draw->AddCircle(a, 6.0f, colour, 16, 2.0f);
            continue;
        }
        if (s.kind != OverlaySegment::Kind::blocked_shadow) {
            draw->AddLine(a, b, colour, 2.0f);
            continue;
        }
        const float length = std::hypot(b.x - a.x, b.y - a.y);
        const float step = 8.0f / std::max(length, 1e-3f); // 5 on, 3 off, in window pixels
        for (float t = 0; t < 1; t += step) {
            const float u = std::min(1.0f, t + step * 5 / 8);
            draw->AddLine(ImVec2(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t),
                          ImVec2(a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u), colour, 2.0f);
        }
    }
}

// The panel, in one body of three sections, each read top to bottom as it appears on screen:
// the settings as controls, the frame's figures, and the explained pixel.
void Preview::draw_panel() {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const PanelPlace place = panel_place(display.x, display.y);
    ImGui::SetNextWindowPos(ImVec2(place.x, place.y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(place.width, place.height), ImGuiCond_FirstUseEver);
    ImGui::Begin("glint preview", nullptr, ImGuiWindowFlags_NoCollapse);
    if (ImGui::CollapsingHeader("Settings", ImGuiTreeNodeFlags_DefaultOpen)) {
        RenderSettings& render = scene_.render;
        if (auto v = enum_combo("mode", frame_.mode)) set("mode", *v);
        if (frame_.mode == Mode::hybrid) {
            if (auto v = enum_combo("raster", frame_.raster)) set("raster", *v);
            if (auto v = enum_combo("resolve", frame_.resolve)) set("resolve", *v);
            int tess = frame_.tessellation;
            if (ImGui::SliderInt("tessellation", &tess, kMinTessellation, kMaxTessellation, "%d",
                                 ImGuiSliderFlags_Logarithmic))
                set("tess", std::to_string(tess));
        }
        int depth = render.max_depth;
        if (ImGui::SliderInt("depth", &depth, 0, kMaxDepth)) set("depth", std::to_string(depth));
        float cutoff = render.min_reflectivity;
        if (ImGui::SliderFloat("cut-off", &cutoff, 0.0f, 1.0f, "%.4f",
                               ImGuiSliderFlags_Logarithmic))
            set("cutoff", std::to_string(cutoff));
        int samples = render.samples;
        if (ImGui::SliderInt("samples (N×N)", &samples, 1, kMaxSamples))
            set("samples", std::to_string(samples));
        if (render.samples > 1)
            if (auto v = enum_combo("antialiasing", render.antialias)) set("aa", *v);
        if (world_)
            if (auto v = enum_combo("structure", world_->accelerator().kind())) set("accel", *v);
        if (auto v = enum_combo("view", view_)) set("view", *v);
    }
    if (ImGui::CollapsingHeader("Frame", ImGuiTreeNodeFlags_DefaultOpen) && job_) {
        const RayCounts rays = job_->rays();
        if (job_->finished())
            ImGui::Text("%dx%d traced in %.3f s", job_->width(), job_->height(), job_->seconds());
        else
            ImGui::Text("%dx%d tracing: %d%%", job_->width(), job_->height(),
                        100 * job_->tiles_done() / (job_->passes() * job_->tile_count()));
        ImGui::Text("world %.1f ms, item buffer %.1f ms",
                    log_.worlds.empty() ? log_.first_world : log_.worlds.back(), item_buffer_ms_);
        ImGui::Text("last frame (UI) %.1f ms",
                    log_.frames.empty() ? log_.first_frame : log_.frames.back());
        // A line of two counters.
        const auto counts = [](const char* format, std::uint64_t a, std::uint64_t b) {
            ImGui::Text(format, static_cast<unsigned long long>(a),
                        static_cast<unsigned long long>(b));
        };
        counts("rays: %llu primary, %llu shadow", rays.primary, rays.shadow);
        counts("      %llu reflection, %llu transmission", rays.reflection, rays.transmission);
        if (frame_.mode == Mode::hybrid) {
            const PrimaryStats p = job_->primary_stats();
            counts("resolve: %llu direct, %llu corrected", p.exact_intersections - p.fallbacks,
                   p.corrected);
            counts("         %llu fallbacks, %llu on edges", p.fallbacks, p.edges);
            counts("         %llu checked, %llu traced in full", p.checked, p.traced);
        }
        if (scene_.render.samples > 1)
            ImGui::Text("antialiasing: %llu pixels took the grid",
                        static_cast<unsigned long long>(job_->refined_pixels()));
    }
    if (ImGui::CollapsingHeader("Pixel", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const auto& [kind, label] :
             {std::pair{OverlaySegment::Kind::primary, "primary (the pixel)"},
              {OverlaySegment::Kind::reflection, "reflection"},
              {OverlaySegment::Kind::transmission, "transmission"},
              {OverlaySegment::Kind::shadow, "shadow, lit"},
              {OverlaySegment::Kind::blocked_shadow, "shadow, blocked (dashed)"}}) {
            ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(overlay_colour(kind)), "%s", label);
            if (kind == OverlaySegment::Kind::primary || kind == OverlaySegment::Kind::transmission)
                ImGui::SameLine(); // two to a line
        }
        if (explanation_.empty())
            ImGui::TextWrapped("Click a pixel to explain it: its ray tree is drawn into the "
                               "scene and written here and on standard output.");
        else if (ImGui::BeginChild("explanation", ImVec2(0, 0), true,
                                   ImGuiWindowFlags_HorizontalScrollbar))
            ImGui::TextUnformatted(explanation_.c_str());
        if (!explanation_.empty()) ImGui::EndChild();
    }
    ImGui::End();
}

void Preview::on_key(int key) {
    if (panel_visible_ && panel_->wants_keyboard()) return; // a control of the panel has it
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
    case GLFW_KEY_G:
        panel_visible_ = !panel_visible_;
        return;
    case GLFW_KEY_R:
        camera_.reset();
        dirty_ = true;
        return;
    case GLFW_KEY_V:
        return set("view", std::string(name_of(static_cast<View>((static_cast<int>(view_) + 1) %
                                                                   kViewCount))));
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET: // within the CLI's limits, as every setting: set() holds them
        return set("depth", std::to_string(std::clamp(
                                scene_.render.max_depth + (key == GLFW_KEY_RIGHT_BRACKET ? 1 : -1),
                                0, kMaxDepth)));
    case GLFW_KEY_COMMA:
    case GLFW_KEY_PERIOD: { // halving from 1e-4 reaches 0, doubling from 0 starts at 1e-4
        const float cutoff = scene_.render.min_reflectivity;
        return set("cutoff", std::to_string(key == GLFW_KEY_PERIOD
                                                 ? std::min(1.0f, std::max(cutoff * 2, 1e-4f))
                                                 : (cutoff / 2 < 1e-4f ? 0.0f : cutoff / 2)));
    }
    case GLFW_KEY_MINUS:
    case GLFW_KEY_EQUAL:
        return set("tess", std::to_string(std::clamp(key == GLFW_KEY_EQUAL
                                                         ? frame_.tessellation * 2
                                                         : frame_.tessellation / 2,
                                                     kMinTessellation, kMaxTessellation)));
    case GLFW_KEY_M:
        return set("raster",
                   std::string(name_of(static_cast<RasterMode>(
                       (static_cast<int>(frame_.raster) + 1) % all_values<RasterMode>().size()))));
    case GLFW_KEY_E:
        return set("resolve", frame_.resolve == Resolve::exact ? "trust" : "exact");
    case GLFW_KEY_T:
        return set("mode", frame_.mode == Mode::hybrid ? "ray" : "hybrid");
    default:
        if (key < GLFW_KEY_1 || key >= GLFW_KEY_1 + kViewCount) return;
        set("view", std::string(name_of(static_cast<View>(key - GLFW_KEY_1))));
    }
}

// A left press and release without moving is a click: the pixel is explained. Moving more than
// kClickSlop pixels first makes it a drag, which orbits.
constexpr double kClickSlop = 3;

void Preview::on_button(int button, int action) {
    glfwGetCursorPos(window_.handle(), &cursor_x_, &cursor_y_);
    if (action == GLFW_PRESS && panel_visible_ && panel_->wants_mouse()) return; // the panel's
    const bool click = action == GLFW_RELEASE && button_ == GLFW_MOUSE_BUTTON_LEFT && !dragged_;
    button_ = action == GLFW_PRESS ? button : -1;
    if (action == GLFW_PRESS) press_x_ = cursor_x_, press_y_ = cursor_y_, dragged_ = false;
    if (click)
        if (const auto pixel = pixel_at(cursor_x_, cursor_y_)) explain_pending_ = pixel;
}

void Preview::on_cursor(double x, double y) {
    const double dx = x - cursor_x_, dy = y - cursor_y_;
    cursor_x_ = x, cursor_y_ = y;
    if (button_ == GLFW_MOUSE_BUTTON_LEFT && !dragged_ &&
        std::hypot(x - press_x_, y - press_y_) <= kClickSlop)
        return; // still a click
    if (button_ == GLFW_MOUSE_BUTTON_LEFT) {
        dragged_ = true;
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
                                       frame_.resolve, view_ == View::difference);
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
    panel_->begin_frame();
    if (panel_visible_) {
        draw_overlay();
        draw_panel();
    }
    panel_->end_frame();
}

std::optional<std::pair<int, int>> Preview::pixel_at(double x, double y) const {
    if (!job_) return std::nullopt;
    int window_width = 1, window_height = 1;
    glfwGetWindowSize(window_.handle(), &window_width, &window_height);
    const int px = static_cast<int>(std::floor(x * job_->width() / std::max(window_width, 1)));
    const int py = static_cast<int>(std::floor(y * job_->height() / std::max(window_height, 1)));
    if (px < 0 || py < 0 || px >= job_->width() || py >= job_->height()) return std::nullopt;
    return std::pair{px, py};
}

void Preview::set(const std::string& name, const std::string& value) {
    switch (
        set_panel_setting({frame_, scene_.render, accel_, view_, panel_visible_}, name, value)) {
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
        if (view_ == View::difference && frame_.mode == Mode::hybrid && job_ &&
            !job_->compares_with_ray())
            dirty_ = true;
        show_base();
        break;
    case Effect::panel:
        break;
    }
    std::printf("glint: panel: %s = %s\n", name.c_str(), value.c_str());
    std::fflush(stdout);
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
    overlay_ = tree_segments(*world_, e);
    explained_ = std::pair{x, y};
    std::fputs(explanation_.c_str(), stdout);
    std::fflush(stdout);
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
        if (frames == 1)
            for (const std::string& assignment : options_.settings) {
                const auto [name, value] = split_assignment(assignment);
                set(name, value);
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

} // namespace

int run_preview(const PreviewOptions& options) {
    Preview preview(options);
    return preview.run();
}

} // namespace glint
