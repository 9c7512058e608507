// glTF skins and morph targets (glTF 2.0 §3.7.2.2 and §3.7.3) as glint poses them (DESIGN §14,
// "Skins and morph targets"): at time t, the morph weights blend each POSITION, NORMAL and
// TANGENT target into the mesh; then each vertex is skinned by Σ wᵢ · (jointᵢ's world matrix ×
// inverseBindMatrixᵢ), normals by that sum's inverse transpose. A skinned mesh is posed in world
// space: the node that places it does not move it. io/gltf_loader.cpp reads and checks them
// (read_skin, read_deformable); GltfMotion (io/gltf_animation.h) poses them at any time.
#pragma once

#include "trace/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Mesh;
struct Primitive;
}

namespace glint {

class GltfAccessors;

// A skin: its joints (node indices) and each one's inverse bind matrix.
struct GltfSkin {
    std::vector<std::size_t> joints;
    std::vector<DMat4> inverse_bind;
};

// One glint mesh that a skin or morph targets move: what it is at rest, and what moves it.
struct Deformable {
    std::uint32_t mesh = 0; // its index in Scene::meshes: a copy of its own, posed in place
    std::size_t node = 0;   // the node that places it, whose morph weights it reads
    std::optional<std::size_t> skin; // index in GltfMotion::skins; none: morph targets only
    // The primitive's attributes as the file gives them (normals and tangents may be absent).
    std::vector<glm::dvec3> positions, normals;
    std::vector<glm::dvec4> tangents;
    // Each target's displacements; an attribute the target lacks is empty.
    struct Target {
        std::vector<glm::dvec3> positions, normals, tangents;
    };
    std::vector<Target> targets;
    // Skinned: `influences` (4 a JOINTS_n/WEIGHTS_n set) joint indices and weights per vertex,
    // the weights summing to 1.
    int influences = 0;
    std::vector<std::uint32_t> joints;
    std::vector<double> weights;
};

// Poses `mesh` (the deformable's copy): morph weights `morph` (one per target, missing ones 0),
// then, for a skinned one, `joint_matrices` (jointᵢ's world × inverse bindᵢ, one per joint).
void deform(const Deformable& d, std::span<const double> morph,
            std::span<const DMat4> joint_matrices, TriangleMesh& mesh);

// What a reader skips with a warning: the feature, and the first place it is met.
using UnusedFeature = std::function<void(const std::string& feature, const std::string& place)>;

// The morph targets of a glTF mesh: its first primitive's (the loader holds every primitive of a
// mesh to as many).
std::size_t morph_target_count(const tinygltf::Mesh& mesh);

// Skin `index` of `model` (in range: the caller checks): its joints exist, its inverse bind
// matrices are MAT4 floats, one a joint, finite and within the coordinate limit.
GltfSkin read_skin(const tinygltf::Model& model, int index, const GltfAccessors& accessors);

// Primitive `p` (at `at`, its `mesh` read already) as a deformable: its morph targets (the
// weights read later, from the node or mesh) and, where `skin` is given, its joints and
// weights, checked: every joint index within the skin's `joint_count`, no weight negative, every
// vertex with some weight. Weights whose sum misses 1 by more than the specification allows are
// renormalized, and `renormalized` says where first.
Deformable read_deformable(const tinygltf::Primitive& p,
                           const std::string& at, const TriangleMesh& mesh,
                           std::optional<std::size_t> joint_count, const GltfAccessors& accessors,
                           const UnusedFeature& unused, std::string& renormalized);

} // namespace glint
