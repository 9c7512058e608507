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
    TriangleMesh mesh; // with texture coordinates where every corner has one (v flipped: down)
    std::optional<Material> material; // from the MTL file; nothing: the scene's default
    std::string material_name;
    std::string texture_file; // the MTL material's map_Kd as named, or empty
    Wrap texture_wrap = Wrap::repeat; // map_Kd's -clamp on: clamp
    std::optional<Texture> texture;   // map_Kd decoded (load_obj), where it could be
    // The MTL material's map_d (docs/SCENES.md, "OBJ cut-outs"): a cut-out at alpha 0.5.
    std::string alpha_file;
    Wrap alpha_wrap = Wrap::repeat;
    std::optional<Texture> alpha; // map_d decoded, its alpha (or grey level) as the image's alpha
};

// The cut-off of an OBJ material with a map_d: a texel whose alpha is below it is cut out.
inline constexpr float kObjAlphaCutoff = 0.5f;

// Appends the part's decoded textures to `textures` and points its material at them: map_Kd as
// the base colour texture, map_d as the cut-out's alpha (the part must have a material).
void add_part_textures(ObjPart& part, std::vector<Texture>& textures);

struct ObjModel {
    std::vector<ObjPart> parts;
    std::vector<std::string> notes;    // what was ignored (lines and points, ...); not naming
                                       // the file, whose path is printed before them
    std::vector<std::string> warnings; // what could not be used (a material library, a texture)
};

// `read_mtl(name)`: the text of a material library the OBJ names (`mtllib`), or nothing if it
// cannot be read (a warning: its materials' faces get the default material). Every error
// (SceneError) names `name` and the line.
ObjModel parse_obj(const std::string& text, const std::string& name,
                   const std::function<std::optional<std::string>(const std::string&)>& read_mtl);

// Reads the file, the material libraries next to it and their materials' textures (map_Kd,
// relative to the OBJ file's directory; one that cannot be read or decoded is a warning).
ObjModel load_obj(const std::filesystem::path& path);

} // namespace glint
