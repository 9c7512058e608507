// One frame, start to finish, in either mode and either precision: the pipeline that render,
// compare, tradeoff and the GL tests share (the preview traces tiles through the same pixel
// path, trace/pixel.h). Hybrid: GL context → shaders → upload → item buffer → exact resolve →
// shading. Ray: primary rays → shading. Every phase is timed on its own.
#pragma once

#include "raster/gl_context.h"
#include "raster/item_buffer.h"
#include "raster/tessellation.h"
#include "trace/render.h"

#include <optional>
#include <string>

namespace glint {

enum class Mode { hybrid, ray };

template <> struct EnumNames<Mode> { static constexpr auto names = name_table("hybrid", "ray"); };

struct FrameSettings {
    Mode mode = Mode::hybrid;
    GlBackend gl = GlBackend::osmesa;
    RasterMode raster = RasterMode::automatic;
    int tessellation = kDefaultTessellation;
    Resolve resolve = Resolve::exact;
    int threads = 0;
    Precision precision = Precision::f32; // double: ray mode only, from a scene (below)
    // Adaptive antialiasing in hybrid mode: also refine where the N×N item buffer's samples of a
    // pixel name more than one object (trace/sampling.h's rule 3). It draws that N×N buffer, and
    // the image may differ from ray mode's (by design: it finds what pixel centres miss), so it
    // is off by default; without it adaptive hybrid equals ray mode byte for byte.
    bool aa_sample_ids = false;
    // One process of several rendering this frame (app/distributed.h): it traces its own tiles
    // and exchanges pixels with the others after each pass. Null: the whole frame here.
    TileExchange* exchange = nullptr;
    // Keep each pixel centre's primary hit (RenderResult::aovs: depth, normal, id) for an EXR.
    bool aovs = false;
};

// The one result of a render, in either mode and either precision.
struct Frame {
    RenderResult result; // image, rays, cut-off weights, primary ids
    PhaseTimes times;
    PrimaryStats primary_stats;                   // hybrid only
    std::optional<ItemBufferResult> items;        // hybrid only: pixel centres (N = 1 or adaptive)
    std::optional<ItemBufferResult> sample_items; // hybrid with N > 1: the N×N sample grid
    std::vector<float> deviations;                // hybrid only: per object, world units
    std::size_t proxies = 0, tessellated = 0;     // hybrid only: how the objects were drawn
    std::string gl_renderer;                      // hybrid only
};

// Hybrid mode's GL pass for a frame of `world` (nothing in ray mode or for an empty scene): the
// context, the item buffers the scene's antialiasing needs, their bins for the exact resolve,
// into `frame` (items, sample_items, deviations, proxies, gl_renderer, times), made on a GL
// thread (frame/gl_pass.h) and waited for. Throws GlError when there is no GL context.
void draw_item_buffers(const World& world, const FrameSettings& settings, Frame& frame);

// Where the frame's primary hits come from: its item buffers (resolved as `resolve` says), or
// every camera ray when it has none. Points into `frame`.
PrimarySource primary_source(const Frame& frame, Resolve resolve);

class GlPass; // frame/gl_pass.h

// From a prepared World (float precision; times.prepare stays 0). Throws GlError when hybrid
// mode cannot get a GL context. `pass`: a GL pass started before the World was built (so that
// its context and shaders were made beside it), or null to start one here where one is needed.
Frame render_frame(const World& world, const FrameSettings& settings,
                   std::atomic<int>* tiles_done = nullptr, GlPass* pass = nullptr);

// From a scene: prepares the World in settings.precision (timed as times.prepare), then renders.
// `geometry`, when given, is the scene's already prepared (float precision; a sweep over one
// scene prepares its meshes once). Double precision is the reference tracer and traces rays
// only: hybrid mode with it throws std::invalid_argument.
Frame render_frame(const Scene& scene, std::optional<AccelKind> accel,
                   const FrameSettings& settings, std::atomic<int>* tiles_done = nullptr,
                   const std::shared_ptr<const SceneGeometry>& geometry = nullptr);

} // namespace glint
