// What the preview's panel draws (preview/session.h; the ImGui frame is preview/panel.h's): the
// settings as controls, the frame's figures, the explained pixel, and its ray tree over the image.
#include "preview/session.h"

#include "frame/difference_maps.h"
#include "io/error.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace glint {

PanelPlace panel_place(float window_width, float window_height) {
    const float width = std::min(360.0f, window_width * 0.45f);
    return {window_width - width - 6, 6, width, window_height - 12};
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

// The reference the live image is compared with, and what the comparison found: per cause its
// pixels in its colour (the cause map's legend), and the heat map's scale.
void Preview::draw_reference_panel() {
    if (!ImGui::CollapsingHeader("Reference", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::Button("exact")) set("reference", "exact");
    ImGui::SameLine();
    if (ImGui::Button("take these settings")) set("reference", "taken");
    ImGui::SameLine();
    if (ImGui::Button("none")) set("reference", "none");
    if (!compares()) {
        ImGui::TextWrapped("No reference: views 7 and 8 (heat and cause maps) compare with the "
                           "exact image; the difference view shows ray against hybrid hits.");
        return;
    }
    ImGui::TextWrapped("against %s", reference_ ? reference_->label.c_str() : "exact");
    if (!comparison_ || !comparison_->ready()) {
        ImGui::Text("comparing…");
        return;
    }
    if (!comparison_->error().empty()) {
        ImGui::TextWrapped("the comparison failed: %s", comparison_->error().c_str());
        return;
    }
    const FrameDifference& d = comparison_->difference();
    ImGui::Text("%llu pixels differ (%.2f%%)", static_cast<unsigned long long>(d.differing),
                100.0 * static_cast<double>(d.differing) / static_cast<double>(d.causes.size()));
    for (std::size_t c = 1; c < kCauses; ++c) {
        const auto cause = static_cast<Cause>(c);
        if (d.tallies[c].pixels == 0) continue;
        const Rgb rgb = cause_colour(cause);
        ImGui::TextColored(
            ImVec4(rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f, 1.0f),
            "%-10s %8llu px, %5.1f%% of the error", std::string(name_of(cause)).c_str(),
            static_cast<unsigned long long>(d.tallies[c].pixels), 100 * d.share(cause));
    }
    ImGui::Text("heat map: 0 (dark violet) to %.3g (yellow), radiance", heat_top(d));
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
    if (scene_.animation && ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextWrapped("%s, %.3g s", scene_.animation->name().c_str(),
                           scene_.animation->duration());
        float t = static_cast<float>(time_);
        if (ImGui::SliderFloat("time (s)", &t, 0.0f,
                               static_cast<float>(std::max(scene_.animation->duration(), 1e-3))))
            set("time", std::to_string(t));
        ImGui::Checkbox("play (space)", &playing_);
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
    draw_reference_panel();
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

} // namespace glint
