// A model file (OBJ, glTF) given where a scene is expected (DESIGN §12, docs/SCENES.md, "Models
// as scenes"): what the file does not bring, a camera that frames the model and lights that
// light it readably, by one documented rule.
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <optional>

namespace glint {

// Where a framing camera looks from (docs/SCENES.md, "Framing"): `front`, head-on down −Z from +Z
// (the side glTF's models face, as the Khronos sample viewer and the screenshots show them: a
// glTF's default); `three_quarter`, from the front a little to the right and above (an OBJ's
// default, the view of glint's earlier waves).
enum class ModelView : std::uint8_t { front, three_quarter };

template <> struct EnumNames<ModelView> {
    static constexpr auto names = name_table("front", "three-quarter");
};

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
    // No note where a time is given and the file has no animation (the preview asks for one
    // whether or not the file has any).
    bool quiet_without_animation = false;
    // `glint render --colour srgb`: a glTF's base colour and emissive textures are decoded from
    // sRGB to linear (their factors are linear already).
    bool srgb = false;
    // `--framing`: where the framing camera looks from; unset, each format's default (ModelView).
    std::optional<ModelView> view;
};

// The framing directions, from the model's centre towards the eye.
inline constexpr DVec3 kFrontDirection{0.0, 0.0, 1.0};
inline constexpr DVec3 kFramingDirection{0.5, 0.4, 1.0}; // three-quarter
// The bounding sphere fills this fraction of the narrower field of view (a margin around it).
inline constexpr double kFramingFill = 0.9;

// Places the camera (eye, look_at, up; fov_y and the image size kept) so that the model's
// bounding sphere (about the centre of its world box, through its farthest placed vertex),
// seen from `view`'s direction, fills kFramingFill of the narrower of the vertical and
// horizontal fields of view. A scene with no bounded object keeps its camera.
void frame_model(Scene& scene, ModelView view);

// The model's bounding sphere: the centre of its world box, and the distance from it to the
// farthest placed mesh vertex (for other shapes, the farthest corner of their placed box);
// nothing for a scene with no bounded object.
struct ModelSphere {
    DVec3 centre;
    double radius;
};
std::optional<ModelSphere> model_sphere(const std::vector<SceneObject>& objects,
                                        const std::vector<TriangleMesh>& meshes);
inline std::optional<ModelSphere> model_sphere(const Scene& scene) {
    return model_sphere(scene.objects, scene.meshes);
}

// The default lights for a model that brings none: a key light above and to the left of the
// camera as seen from the model's centre, at √2 times the camera's distance from that centre
// (for a framing camera and a file's camera alike), a weaker fill light at the eye, and a
// little ambient light; colours sum to at most 1 on a surface facing both, so a white material
// stays below saturation. `centre`: the model's centre where the caller knows it better (a glTF
// model's before its animation), else model_sphere's.
void light_model(Scene& scene, std::optional<DVec3> centre = std::nullopt);

// An OBJ file as a scene: each part (one per MTL material) an object of the model's own
// coordinates, framed and lit by the rules above.
Scene obj_scene(const std::filesystem::path& path, const ModelOptions& options = {});

} // namespace glint
