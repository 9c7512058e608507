// glTF animations (glTF 2.0 §3.11) as glint plays them (DESIGN §13, "Animation time"): node
// translation, rotation and scale channels, each sampler interpolated as the specification says
// (STEP; LINEAR, rotations by its slerp; CUBICSPLINE, Hermite with the tangents scaled by the key
// interval), holding its first value before the first key and its last after the last.
// io/gltf_loader.cpp reads and checks them; GltfMotion then places a loaded scene at any time.
#pragma once

#include "io/gltf_skin.h"
#include "trace/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
class Node;
}

namespace glint {

class GltfAccessors;

enum class Interpolation : std::uint8_t { step, linear, cubic_spline };
enum class TrsPath : std::uint8_t { translation, rotation, scale, weights };

// One sampler as a channel reads it.
struct KeyFrames {
    std::vector<double> times; // strictly increasing, finite
    // `width` numbers a key (3, or 4 for rotations: x, y, z, w); CUBICSPLINE keeps three
    // elements a key, in-tangent, value, out-tangent.
    std::vector<double> values;
    int width = 3; // morph weights: one a target

    Interpolation interpolation = Interpolation::linear;
};

// The keys' value at time t (unused components 0); a rotation comes back a unit quaternion.
glm::dvec4 sample_keys(const KeyFrames& keys, double t, bool rotation);
// Morph weights' keys at time t: `width` values, each interpolated as a translation's would be.
std::vector<double> sample_weights(const KeyFrames& keys, double t);

// A node's local transform as glTF composes it: T · R · S.
struct NodeTrs {
    DVec3 translation{0.0};
    glm::dvec4 rotation{0, 0, 0, 1}; // x, y, z, w: a unit quaternion
    DVec3 scale{1.0};
};
DMat4 trs_matrix(const NodeTrs& trs);
// A node's own TRS (absent parts the identity's), its rotation normalised; the loader has
// checked the arrays' sizes and that the rotation is not zero.
NodeTrs node_trs(const tinygltf::Node& node);

// What the loader records of a model's node tree, the chosen animation and the skins and morph
// targets it moves, so that poses at other times need no second reading of the file. A model
// with skins or morph targets and no animation asked for has one too, with no channels: it poses
// them once, at rest.
class GltfMotion final : public Animation {
  public:
    struct Channel {
        std::size_t node;
        TrsPath path;
        std::size_t keys; // index in `samplers`
    };
    struct Node {
        DMat4 matrix{1.0}; // its `matrix`, for a node no channel moves
        NodeTrs trs;       // its own TRS
        bool has_matrix = false;
        std::vector<std::size_t> children;
    };

    std::string label;
    std::vector<Node> nodes;
    std::vector<std::size_t> roots;
    std::vector<KeyFrames> samplers;
    std::vector<Channel> channels; // translation, rotation and scale
    std::vector<Channel> weight_channels; // morph weights, path `weights`
    // Per node, the indices of the channels that move it (made with `channels`).
    std::vector<std::vector<std::size_t>> channels_of;
    // What the scene's parts hang on: per object and per light, its node (kNoNode: a skinned
    // object, posed in world space, or a directional light, which does not follow); the file
    // camera's node, when the scene looks through one.
    static constexpr std::size_t kNoNode = ~std::size_t{0};
    std::vector<std::size_t> object_nodes, light_nodes;
    // Per object, its instance's matrix after its node's (EXT_mesh_gpu_instancing, io/
    // gltf_instances.h); empty where the model has no instances.
    std::vector<DMat4> object_offsets;
    std::optional<std::size_t> camera_node;
    // The skins and the meshes they and morph targets move; per node, its morph weights as the
    // file gives them (the node's, else its mesh's, else zeros; empty for a node without).
    std::vector<GltfSkin> skins;
    std::vector<Deformable> deformables;
    std::vector<std::vector<double>> rest_weights;
    // Whether an animation was asked for and read: without, this only poses skins and morph
    // targets at rest, and is not the scene's Animation.
    bool animated = false;

    // Node k's local matrix at time t; none: at rest, as the file places it.
    DMat4 local(std::size_t k, std::optional<double> t) const;
    // Whether a channel moves node k.
    bool moves(std::size_t k) const;
    // Every node's world matrix at time t (none: at rest).
    std::vector<DMat4> world(std::optional<double> t) const;
    // Node k's morph weights at time t (none: at rest).
    std::vector<double> weights(std::size_t k, std::optional<double> t) const;
    // Poses every deformable's mesh in `meshes` with the nodes at `world` and the weights at t.
    void deform(std::vector<TriangleMesh>& meshes, const std::vector<DMat4>& world,
                std::optional<double> t) const;

    std::string name() const override { return label; }
    double duration() const override;
    void pose(Scene& scene, double t) const override;
    std::vector<std::uint32_t> moving_meshes() const override;
};

// Animation `index` of `model` (in range: the caller checks), its channels and keys checked
// (docs/SCENES.md, "Animation"): key times finite and strictly increasing, outputs of the
// channel's type and count (morph weights: one a target of the node's mesh), rotations not
// zero, no animated node placed by a matrix; channels without a node are skipped through
// `unused`. Its nodes are sized for the model and left for the loader's walk to fill (the
// nodes' own TRS, children, roots, and what hangs on them).
std::shared_ptr<GltfMotion> read_gltf_animation(const tinygltf::Model& model, int index,
                                                const GltfAccessors& accessors,
                                                const UnusedFeature& unused);

// A file camera's eye, look-at point and up from its node's world matrix (DESIGN §12: the
// node's −Z is the viewing direction, its +Y up).
void place_camera(Camera& camera, const DMat4& world);

} // namespace glint
