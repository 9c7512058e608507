// glTF's EXT_mesh_gpu_instancing (docs/SCENES.md, "glTF"): a node that draws its mesh many
// times, each instance placed by its own translation, rotation and scale after the node's world
// matrix. Every instance shares the node's meshes (and their prepared structures): to glint's
// top level an instance is one more object, a transform over a mesh (trace/world.h).
#pragma once

#include "trace/scene.h"

#include <string>
#include <vector>

namespace tinygltf {
class Node;
}

namespace glint {

class GltfAccessors;

// Node `node`'s instances (at `at`, its JSON pointer) as local matrices T · R · S, or none where
// it has no EXT_mesh_gpu_instancing. Its TRANSLATION, ROTATION and SCALE accessors (floats, or
// KHR_mesh_quantization's integers) must have one count; rotations not zero; every value finite
// and within the coordinate limit. At most `max_count` instances.
std::vector<DMat4> read_instances(const tinygltf::Node& node, const std::string& at,
                                  const GltfAccessors& accessors, std::size_t max_count);

} // namespace glint
