// `glint explain` and the preview's click (docs/EXPLAIN.md): one pixel of a frame explained,
// from its ray tree as the render's own path computed it (trace/explain.h), written for people
// (the lecture's notation, numbers filled in) and as JSON (the schema in docs/EXPLAIN.md). World
// coordinates are the scene's (the tracer's are camera-relative: the eye is added back).
#pragma once

#include "frame/frame.h"
#include "trace/explain.h"

#include <string>

namespace glint {

// Explains sample (a, b) of pixel (x, y) of the frame `settings` renders of `world` (both in
// range: the caller checks): hybrid mode draws the item buffers first; adaptive antialiasing with
// N > 1 renders the whole frame first, since whether a pixel is refined depends on its
// neighbours.
PixelExplanation explain_frame_pixel(const World& world, const FrameSettings& settings, int x,
                                     int y, int a, int b);

// The explanation for people: the tree top down, each ray with its hit, its object-space ray,
// normals, per-light terms and shadow verdicts, the children's weights, R_p with the numbers filled
// in, and the bytes. `scene` is the World's (names, M, the eye); `what` heads it ("pixel (x, y) of
// scenes/default.json, hybrid …").
std::string explanation_text(const Scene& scene, const World& world, const PixelExplanation& e,
                             const std::string& what);

// The same as JSON, indented, schema "glint-explain/1" (docs/EXPLAIN.md).
std::string explanation_json(const Scene& scene, const World& world, const PixelExplanation& e,
                             const std::string& scene_path, const std::string& settings);

} // namespace glint
