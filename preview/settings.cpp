#include "preview/settings.h"

#include "io/error.h"
#include "preview/preview.h"

#include <stdexcept>
#include <vector>

namespace glint {

const std::string_view kPreviewKeys = R"(glint preview keys
  left drag         orbit around look_at
  right/middle drag pan
  wheel             dolly towards / away from look_at
  left click        explain the pixel: its ray tree drawn, the explanation in the panel
  G                 the panel (and the explained tree) on / off
  R                 reset the camera to the scene's
  1 … 8             view: final image, item buffer, depth, normals, ray vs hybrid (or vs the
                    reference), reflection depth, heat map, cause map (against the reference)
  V                 next view
  [ ]               max reflection depth − / +
  , .               reflection cut-off (min reflectivity) ÷2 / ×2
  - =               tessellation ÷2 / ×2 (mesh and auto raster modes)
  M                 raster mode: mesh / proxy / auto
  E                 resolve mode: exact / trust
  T                 tracer: hybrid (item buffer) / ray
  space             an animated model: play / pause (the panel's Animation slider sets the time)
  P                 save a screenshot PNG
  H                 this list
  Esc, Q            quit
)";

const std::vector<std::string> kPreviewSettings = {
    "mode", "raster", "resolve", "depth", "cutoff", "tess", "samples",
    "aa",   "accel",  "view",    "panel", "reference", "time"};

namespace {

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

} // namespace

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
    if (name == "reference") {
        if (value != "none" && value != "exact" && value != "taken")
            throw std::invalid_argument(name + "=" + value +
                                        ": expected none, exact or taken (the settings now)");
        return s.reference = value, Effect::reference;
    }
    if (name == "time") return s.time = parse_number(name, value, 0, 1e9), Effect::pose;
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

void check_preview_setting(const std::string& assignment) {
    FrameSettings frame;
    RenderSettings render;
    std::optional<AccelKind> accel;
    View view = View::final;
    bool panel = true;
    std::string reference;
    double time = 0;
    const auto [name, value] = split_assignment(assignment);
    set_panel_setting({frame, render, accel, view, panel, reference, time}, name, value);
}

} // namespace glint
