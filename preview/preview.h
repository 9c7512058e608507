// `glint preview`: a window on a scene. The GL item buffer (with a flat-shaded colour image from
// the same pass) shows at once; the hybrid trace then refines it tile by tile on worker threads
// while the UI thread keeps handling input. Any change of camera or setting restarts the trace.
#pragma once

#include "frame/frame.h"
#include "preview/views.h"
#include "trace/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

struct PreviewOptions {
    Scene scene;
    std::string scene_name; // for the title and screenshot names
    std::optional<AccelKind> accel;
    FrameSettings frame;     // mode, raster, tessellation, resolve, threads (the window is the GL)
    View view = View::final; // the view shown first
    // Scripted use: draw at least `frames` frames (orbiting `spin` degrees each), then wait until
    // the trace has fully refined, save the framebuffer to `screenshot` (if given) and exit.
    int frames = 0;
    std::filesystem::path screenshot;
    double spin = 0;
    // Scripted: keys pressed one a frame from the second frame on, as their characters ('[', 'M').
    std::string keys;
    // Scripted: the panel's settings, "name=value" (preview_setting_names), set through the panel's
    // own path on the second frame, in order.
    std::vector<std::string> settings;
    // Scripted: the pixel clicked once the trace has finished (it is explained, and its tree
    // drawn).
    std::optional<std::pair<int, int>> click;
    bool panel = true; // the panel (and a clicked pixel's tree) shown; G toggles it
    double time = 0;   // where an animated model is posed first (`--time`)

    bool scripted() const { return frames > 0 || !screenshot.empty(); }
};

// The settings the panel controls, by the names --set takes: mode, raster, resolve, depth,
// cutoff, tess, samples, aa, accel, view, panel, reference, time.
extern const std::vector<std::string> kPreviewSettings;

// Where the panel first opens in a window of this size (window coordinates): along the right
// edge, at most 360 wide, 45% of the window on a small one.
struct PanelPlace {
    float x, y, width, height;
};
PanelPlace panel_place(float window_width, float window_height);

// Checks a "name=value" the panel would accept; throws std::invalid_argument saying what is wrong.
void check_preview_setting(const std::string& assignment);

// The keys, as H prints them (README's list is this text).
extern const std::string_view kPreviewKeys;

// Opens the window and runs until it closes (or, scripted, until done). Returns the exit code.
// Throws NoDisplayError when there is no display, GlError when the window has no usable GL.
int run_preview(const PreviewOptions& options);

} // namespace glint
