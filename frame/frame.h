// One frame, start to finish, in either mode and either precision: the pipeline that render,
// compare, tradeoff and the GL tests share (the preview traces tiles through the same pixel
// path, trace/pixel.h). Hybrid: GL context → shaders → upload → item buffer → exact resolve →
// shading. Ray: primary rays → shading. Every phase is timed on its own.
#pragma once

#include "frame/frame_settings.h"
#include "frame/gl_pass.h"

#include <atomic>
#include <memory>
#include <optional>

namespace glint {

// Hybrid mode's GL pass for a frame of `world` (nothing in ray mode or for an empty scene): the
// context, the item buffers the scene's antialiasing needs, their bins for the exact resolve,
// into `frame` (items, sample_items, deviations, proxies, gl_renderer, times), made on a GL
// thread (frame/gl_pass.h) and waited for. Throws GlError when there is no GL context.
void draw_item_buffers(const World& world, const FrameSettings& settings, Frame& frame);

// Where the frame's primary hits come from: its item buffers (resolved as `resolve` says), or
// every camera ray when it has none. Points into `frame`.
PrimarySource primary_source(const Frame& frame, Resolve resolve);

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
