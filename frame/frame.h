// One frame, start to finish, in either mode: the pipeline `render` and `compare` share.
// Hybrid: GL context → shaders → upload → item buffer → exact resolve → shading.
// Ray: primary rays → shading. Every phase is timed on its own.
#pragma once

#include "raster/gl_context.h"
#include "raster/item_buffer.h"
#include "raster/tessellation.h"
#include "trace/render.h"

#include <optional>
#include <string>

namespace glint {

enum class Mode { hybrid, ray };

template <> struct EnumNames<Mode> {
    static constexpr std::array<std::string_view, 2> names = {"hybrid", "ray"};
};

struct FrameSettings {
    Mode mode = Mode::hybrid;
    GlBackend gl = GlBackend::osmesa;
    RasterMode raster = RasterMode::mesh;
    int tessellation = kDefaultTessellation;
    Resolve resolve = Resolve::exact;
    int threads = 0;
};

struct PhaseTimes {
    double context = 0; // GL context creation
    double compile = 0; // shader compilation (first use; ~0.2 s on llvmpipe)
    double upload = 0;  // tessellation and buffer upload
    double raster = 0;  // drawing the item buffer and reading it back
    double primary = 0; // resolving primary hits (hybrid) or casting primary rays (ray)
    double shading = 0; // shading, shadow and reflection rays

    double primary_visibility() const { return raster + primary; }
    double total() const { return context + compile + upload + raster + primary + shading; }
};

struct Frame {
    RenderResult result;
    std::vector<Hit> primary;
    PhaseTimes times;
    PrimaryStats primary_stats;            // hybrid only
    std::optional<ItemBufferResult> items; // hybrid only
    std::vector<float> deviations;         // hybrid only: per object, world units
    std::string gl_renderer;               // hybrid only
};

// Throws GlError when hybrid mode cannot get a GL context.
Frame render_frame(const World& world, const FrameSettings& settings,
                   std::atomic<int>* tiles_done = nullptr);

} // namespace glint
