// Compressed glTF geometry decoded through Debian's libraries, before the loader reads the model
// (docs/SCENES.md, "glTF"): KHR_draco_mesh_compression (libdraco) and EXT_meshopt_compression
// (libmeshoptimizer). Each leaves plain accessors and buffer views over decoded bytes, so the
// rest of the loader reads a compressed model as it reads a plain one; every index, offset and
// count is checked first, and bytes that do not decode are a SceneError naming the place.
#pragma once

#include <string>

namespace tinygltf {
class Model;
}

namespace glint {

// Each primitive with KHR_draco_mesh_compression: its indices and the attributes the extension
// names become new accessors over a new buffer of the decoded values, in the component types the
// primitive's own accessors give.
void decode_draco(tinygltf::Model& model, const std::string& name);

// Each buffer view with EXT_meshopt_compression: its bytes decoded (vertex or index codec, then
// the filter) from the compressed buffer the extension names, into a new buffer.
void decode_meshopt(tinygltf::Model& model, const std::string& name);

} // namespace glint
