// The file a command is given as its scene, read by its extension: the one entry point to every
// reader (io/json_loader.h, io/nff_loader.h, io/obj_loader.h, io/gltf_loader.h).
#pragma once

#include "io/error.h"
#include "io/model_scene.h"

#include <filesystem>

namespace glint {

// The file a command is given as its scene, read by its extension (any case): .json, .nff, or a
// model, .obj, .gltf or .glb (io/model_scene.h); any other is an error naming the five.
// `options.size` replaces the camera's image size before a model is framed; `options.camera`
// picks a glTF camera and is an error for the other formats.
Scene load_scene(const std::filesystem::path& path, const ModelOptions& options = {});

} // namespace glint
