// The settings the preview's panel controls, by the names `--set` takes, parsed in one place:
// the panel's controls, its keys and a scripted --set all change a setting through
// set_panel_setting, which holds each to the command line's limits.
#pragma once

#include "frame/frame.h"
#include "preview/views.h"

#include <optional>
#include <string>
#include <utility>

namespace glint {

// What the panel controls, wherever it lives (the preview's members, or a scratch copy when a
// scripted --set is checked).
struct PanelState {
    FrameSettings& frame;
    RenderSettings& render;
    std::optional<AccelKind>& accel;
    View& view;
    bool& panel;
    std::string& reference; // none, exact, or taken (the settings as they are when it is set)
    double& time;           // seconds: where an animated model is posed (DESIGN §13, §14)
};

// What a change of setting asks of the preview.
enum class Effect { retrace, upload, new_world, view, panel, reference, pose };

// Sets one of the panel's settings by name: the panel's controls and --set both come here.
// Throws std::invalid_argument saying what is wrong.
Effect set_panel_setting(const PanelState& s, const std::string& name, const std::string& value);

// "name=value" as its two parts; throws std::invalid_argument without the '='.
std::pair<std::string, std::string> split_assignment(const std::string& assignment);

} // namespace glint
