// What a frame is asked for (FrameSettings) and what it gives back (Frame), in either mode and
// either precision: the types frame/frame.h's render_frame and frame/gl_pass.h's GL pass share.
#pragma once

#include "raster/gl_context.h"
#include "raster/item_buffer.h"
#include "raster/tessellation.h"
#include "trace/render.h"

#include <optional>
#include <string>
#include <vector>

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
    // One process of several rendering this frame (app/distributed.h): it traces the tiles it
    // claims and sends them to rank 0, which holds the whole image. Null: the whole frame here.
    TileExchange* exchange = nullptr;
    // Keep each pixel centre's primary hit (RenderResult::aovs: depth, normal, id) for an EXR.
    bool aovs = false;
    // Keep each pixel's object id (RenderResult::ids), which compare and tradeoff (from the
    // command line or Python) read; `glint render` does without. A frame on MPI ranks keeps
    // them whatever this says: its exchange sends them.
    bool ids = true;
    // Keep the float images (RenderResult::radiance, clamped), which an EXR, compare, tradeoff,
    // the preview and the Python module read; `glint render` to a linear PNG does without (the
    // display bytes are all it writes). A frame on MPI ranks keeps them whatever this says.
    bool radiance = true;
    // Set from another thread to stop the frame between tiles (the Python module's Ctrl-C): the
    // frame returned is then incomplete, and its caller says so (frame_cancelled). Null: never.
    const std::atomic<bool>* cancel = nullptr;
    // The tiles' schedule as these settings ask for it.
    TileProgress progress(std::atomic<int>* tiles_done) const {
        return {threads, tiles_done, exchange, cancel};
    }
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

} // namespace glint
