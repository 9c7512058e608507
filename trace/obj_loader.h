// Wavefront OBJ meshes (with their MTL materials), read with tinyobjloader for JSON scenes'
// {"shape": "mesh", "file": "x.obj"} objects (docs/SCENES.md, "OBJ meshes").
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace glint {

// One material's triangles of an OBJ file, in the file's coordinates.
struct ObjPart {
    TriangleMesh mesh;
    std::optional<Material> material; // from the MTL file; nothing: the scene's default
    std::string material_name;
};

struct ObjModel {
    std::vector<ObjPart> parts;
    std::vector<std::string> notes; // what was ignored (missing MTL file, lines and points, ...)
};

// `read_mtl(name)`: the text of a material library the OBJ names (`mtllib`), or nothing if it
// cannot be read. Every error (SceneError) names `name` and the line.
ObjModel parse_obj(const std::string& text, const std::string& name,
                   const std::function<std::optional<std::string>(const std::string&)>& read_mtl);

// Reads the file and the material libraries next to it.
ObjModel load_obj(const std::filesystem::path& path);

} // namespace glint
