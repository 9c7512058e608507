// A glTF file's container, checked before tinygltf parses it (docs/SCENES.md, "glTF"): the GLB
// chunks, the JSON's nesting, required extensions, the buffers' sizes against their files and
// the byte ranges of images in buffer views, each refused with the file and the place; then
// tinygltf's parse with glint's hooks (images kept as their encoded bytes, external buffers
// served from what the check read). io/gltf_loader.cpp reads the parsed model into a scene.
#pragma once

#include "io/gltf_loader.h"

// As io/tinygltf.cpp compiles it: images are glint's to decode.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <set>
#include <string>
#include <vector>

namespace glint {

// Extensions glint reads; a file that requires any other is refused.
extern const std::set<std::string> kKnownExtensions;

// The JSON pointer of element `index` of a top-level array: "/accessors/3".
std::string pointer(const std::string& array, std::size_t index);

// The URI as a file name: %XX decoded, as tinygltf decodes it before asking for the file.
std::string decode_uri(const std::string& uri);

bool is_data_uri(const std::string& uri);

// The model in `bytes` (glTF JSON or GLB), named `name`, its external buffers read through
// `files`: checked, then parsed by tinygltf. What the check leaves unused goes to `warnings`.
// Throws SceneError naming the file and the place.
tinygltf::Model read_gltf_container(const std::string& bytes, const std::string& name,
                                    const ModelFiles& files, std::vector<std::string>& warnings);

} // namespace glint
