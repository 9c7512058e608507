// The preview's window and its state: one class whose members are defined by job, a file each:
// preview.cpp the event loop (and applying a setting, explaining a pixel); session_input.cpp keys
// and the mouse; session_present.cpp restarting the trace and putting its image on screen;
// session_panel.cpp what the panel and the explained ray tree draw.
#pragma once

#include "preview/comparison.h"
#include "preview/frame_log.h"
#include "preview/orbit_camera.h"
#include "preview/panel.h"
#include "preview/preview.h"
#include "preview/ray_overlay.h"
#include "preview/refiner.h"
#include "preview/views.h"
#include "preview/window.h"
#include "raster/item_buffer.h"

#include <glad/gl.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace glint {

// The window on one scene (run_preview): what it shows, what it traces, and its input.
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
    // Poses an animated model at time_ (its nodes, skins and morph targets): the moved meshes'
    // BVHs built again, the item buffer uploaded again, the frame traced again.
    void pose();
    // Explains pixel (x, y) of the finished trace: the text to stdout and the panel, the tree's
    // segments to the overlay.
    void explain(int x, int y);
    void draw_panel();
    void draw_reference_panel();
    void draw_overlay();
    // The comparison against a reference (preview/comparison.h): whether the view asks for one
    // (a reference is set, or the heat or cause map is shown: against exact by default), and
    // whether the current view comes from the refiner's tiles.
    bool compares() const;
    bool from_refiner() const;
    // Starts comparing the finished trace with the reference; forgets the one under way.
    void start_comparison();
    void retire_comparison();
    // The comparison's image for the current view, once it is ready; null otherwise.
    const Image* compared_view() const;
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
    // An animated model's time (seconds), whether it plays, and the geometry of its last pose
    // (the meshes its skins and morph targets moved prepared again; none before a pose).
    double time_ = 0;
    bool playing_ = false;
    std::shared_ptr<const SceneGeometry> posed_geometry_;
    // The reference the live image is compared with: none, exact or taken (the settings as they
    // were when taken); its comparison for the current camera and settings, and comparisons no
    // longer wanted that are still finishing (dropped once ready: no wait on the UI thread).
    std::string reference_choice_ = "none";
    std::optional<Side> reference_;
    std::shared_ptr<ReferenceComparison> comparison_;
    std::vector<std::shared_ptr<ReferenceComparison>> retired_;
    bool comparison_shown_ = false;
    // A hybrid reference's item buffer where its raster mode or tessellation is not the view's.
    ItemBuffer reference_items_;
    std::optional<std::pair<RasterMode, int>> reference_uploaded_;
    FrameLog log_;
    // After the window: ImGui's callbacks chain to the preview's, set before it, and it is gone
    // before the window's GL context.
    std::optional<Panel> panel_;
    Refiner refiner_; // last: its workers stop before anything they read goes
};

} // namespace glint
