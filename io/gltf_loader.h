// glTF 2.0 models (.gltf with external or embedded buffers, .glb) as scenes, read with tinygltf
// (docs/SCENES.md, "glTF"; DESIGN §12). Every error (SceneError) names the file and the place:
// a JSON pointer ("/accessors/3"), or the GLB chunk.
#pragma once

#include "io/model_scene.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace glint {

// The bytes of a file a glTF names beside itself (an external buffer or image), by its URI
// decoded (%20 → ' '), or nothing with `why` saying what went wrong.
using ModelFiles =
    std::function<std::optional<std::string>(const std::string& uri, std::string& why)>;

// A glTF (JSON text) or GLB (binary) file's bytes as a scene; `name` stands for the file.
Scene parse_gltf(const std::string& bytes, const std::string& name, const ModelFiles& files,
                 const ModelOptions& options = {});

// Reads the file, and the files it names relative to its directory.
Scene load_gltf(const std::filesystem::path& path, const ModelOptions& options = {});

} // namespace glint
