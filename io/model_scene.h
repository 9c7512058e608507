// A model file (OBJ, glTF) given where a scene is expected (DESIGN §12, docs/SCENES.md, "Models
// as scenes"): what the file does not bring, a camera that frames the model and lights that
// light it readably, by one documented rule.
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <optional>

namespace glint {

// What the command line asks of a model file: which of its cameras, and the image size that
// the framing rule fits the model into.
struct ModelOptions {
    std::optional<int> camera; // `--camera N`: look through a glTF file's camera N
    std::optional<std::pair<int, int>> size; // `--size`: width and height
    // `--time T` (or a sequence's first frame): place a glTF model's nodes at time T of its
    // animation `animation` (`--animation K`, default the first; DESIGN §13). Unset: the
    // nodes' own TRS, and no animation is read.
    std::optional<double> time;
    int animation = 0;
    // `glint render --colour srgb`: a glTF's base colour and emissive textures are decoded from
    // sRGB to linear (their factors are linear already).
    bool srgb = false;
};

// The framing rule's fixed viewing direction: from the front (+Z, the side glTF's and most OBJ
// models face), a little to the right and above, towards the model's centre.
inline constexpr DVec3 kFramingDirection{0.5, 0.4, 1.0};
// The bounding sphere fills this fraction of the narrower field of view (a margin around it).
inline constexpr double kFramingFill = 0.9;

// Places the camera (eye, look_at, up; fov_y and the image size kept) so that the model's
// bounding sphere (about the centre of its world box, through its farthest placed vertex),
// seen along kFramingDirection, fills kFramingFill of the narrower of the vertical and
// horizontal fields of view. A scene with no bounded object keeps its camera.
void frame_model(Scene& scene);

// The default lights for a model that brings none: a key light above and to the left of the
// camera, a weaker fill light at the eye, and a little ambient light; colours sum to at most 1
// on a surface facing both, so a white material stays below saturation.
void light_model(Scene& scene);

// An OBJ file as a scene: each part (one per MTL material) an object of the model's own
// coordinates, framed and lit by the rules above.
Scene obj_scene(const std::filesystem::path& path, const ModelOptions& options = {});

} // namespace glint
