#include "io/gltf_loader.h"

#include "io/error.h"
#include "io/gltf_accessors.h"
#include "io/gltf_animation.h"
#include "io/gltf_container.h"
#include "io/gltf_decoders.h"
#include "io/gltf_instances.h"
#include "io/gltf_materials.h"
#include "io/gltf_skin.h"
#include "io/model_scene.h"
#include "io/read_text.h"
#include "io/scene_check.h"
#include "trace/shapes/table.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>

namespace glint {
namespace {

// Objects a model may place (nodes × primitives): beyond, a small file would fill the memory.
constexpr std::size_t kMaxModelObjects = std::size_t{1} << 22;

// The component types of positions and texture coordinates, and of normals and tangents: float,
// and KHR_mesh_quantization's integers (positions and coordinates plain or normalized, as the
// accessor says; directions normalized, their length restored on reading).
constexpr std::initializer_list<int> kPositionTypes = {
    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
constexpr std::initializer_list<int> kDirectionTypes = {
    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT};

// glint's reading of a parsed model: its accessors checked and read, its node tree walked into
// placed meshes, its materials mapped to Phong (docs/SCENES.md, "glTF").
class Reader {
  public:
    Reader(const tinygltf::Model& model, const std::string& name, const ModelFiles& files,
           const ModelOptions& options, std::vector<std::string> warnings)
        : m_(model), name_(name), options_(options), accessors_(model, name),
          materials_(model, name, files, options, scene_,
                     [this](const std::string& feature, const std::string& place) {
                         unused(feature, place);
                     }) {
        scene_.warnings = std::move(warnings);
    }

    Scene read() {
        if (options_.size) std::tie(scene_.camera.width, scene_.camera.height) = *options_.size;
        if (options_.time) read_animation();
        prepare_deformation();
        walk_nodes();
        if (motion_ && !motion_->deformables.empty()) {
            const std::optional<double> t = motion_->animated ? options_.time : std::nullopt;
            motion_->deform(scene_.meshes, motion_->world(t), t);
        }
        if (!renormalized_.empty())
            scene_.warnings.push_back(name_ + ": skin weights that do not sum to 1 are "
                                      "renormalized (the first: " + renormalized_ + ")");
        camera();
        lights();
        if (motion_ && motion_->animated) scene_.animation = motion_;
        if (!unused_.empty()) {
            std::string list;
            for (const auto& [feature, place] : unused_)
                list += (list.empty() ? "" : ", ") + feature + " (" + place + ")";
            scene_.warnings.push_back(name_ + ": glTF features glint does not use, the model " +
                                      "renders without them: " + list);
        }
        check_scene(scene_, [this](const std::string& path) { return place_of(path); });
        return std::move(scene_);
    }

  private:
    [[noreturn]] void fail(const std::string& place, const std::string& what) const {
        throw SceneError(name_ + ": " + place + ": " + what);
    }
    void unused(const std::string& feature, const std::string& place) {
        unused_.emplace(feature, place); // the first place of each
    }

    // ---- meshes ----------------------------------------------------------------------------

    // A drawable primitive as glint has it: its mesh (in Scene::meshes) and material.
    struct Part {
        std::uint32_t mesh, material;
    };

    // The glint meshes (one per drawable primitive) of glTF mesh `index`, with their materials:
    // made on first use, placed again by every further node (instances).
    const std::vector<Part>& mesh(int index, const std::string& use) {
        if (index < 0 || static_cast<std::size_t>(index) >= m_.meshes.size())
            fail(use, "no mesh " + std::to_string(index));
        if (const auto it = meshes_.find(index); it != meshes_.end()) return it->second;
        std::vector<Part> parts;
        const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(index)];
        check_targets(mesh, pointer("meshes", static_cast<std::size_t>(index)));
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::string at =
                pointer("meshes", static_cast<std::size_t>(index)) + "/primitives/" +
                std::to_string(p);
            std::optional<TriangleMesh> triangles = primitive(mesh.primitives[p], at);
            if (!triangles) continue;
            const std::uint32_t material = primitive_material(mesh.primitives[p], at);
            parts.push_back({static_cast<std::uint32_t>(scene_.meshes.size()), material});
            scene_.meshes.push_back(std::move(*triangles));
        }
        return meshes_.emplace(index, std::move(parts)).first->second;
    }

    std::uint32_t primitive_material(const tinygltf::Primitive& p, const std::string& at) {
        if (p.material < 0) return 0;
        if (static_cast<std::size_t>(p.material) >= m_.materials.size())
            fail(at + "/material", "no material " + std::to_string(p.material));
        return materials_.material(p.material);
    }

    // A primitive's triangles, or nothing for points and lines (not drawn, with a warning).
    std::optional<TriangleMesh> primitive(const tinygltf::Primitive& p, const std::string& at) {
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode <= TINYGLTF_MODE_LINE_STRIP) {
            unused("points and lines (mode " + std::to_string(mode) + ")", at);
            return std::nullopt;
        }
        if (mode > TINYGLTF_MODE_TRIANGLE_FAN) fail(at + "/mode", "unknown primitive mode");
        const auto attribute = [&](const char* key) {
            const auto it = p.attributes.find(key);
            return it == p.attributes.end() ? -1 : it->second;
        };
        if (attribute("POSITION") < 0) fail(at + "/attributes", "a primitive needs a POSITION");
        const std::string positions_at = at + "/attributes/POSITION";
        const std::vector<double> xyz =
            accessors_.read_accessor(attribute("POSITION"), TINYGLTF_TYPE_VEC3, 3,
                          kPositionTypes, positions_at, kMaxMeshVertices);
        const std::size_t n = xyz.size() / 3;
        TriangleMesh mesh;
        mesh.vertices.reserve(n);
        for (std::size_t i = 0; i < n; ++i)
            mesh.vertices.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        mesh_places_.push_back(
            {pointer("accessors", static_cast<std::size_t>(attribute("POSITION"))), -1});
        if (attribute("NORMAL") >= 0) {
            const std::vector<double> normals =
                accessors_.read_accessor(attribute("NORMAL"), TINYGLTF_TYPE_VEC3, 3,
                              kDirectionTypes, at + "/attributes/NORMAL", n);
            if (normals.size() != xyz.size())
                fail(at + "/attributes/NORMAL", "has a count other than POSITION's");
            for (std::size_t i = 0; i < n; ++i) {
                const glm::dvec3 v(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
                const double length = glm::length(v);
                // Where a normal is zero or not finite, the facet's stands in (as for OBJ).
                mesh.normals.emplace_back(length > 0 && std::isfinite(length) ? v / length
                                                                               : glm::dvec3(0));
            }
        }
        for (const auto& [key, uvs] :
             {std::pair{"TEXCOORD_0", &mesh.uvs}, std::pair{"TEXCOORD_1", &mesh.uvs1}}) {
            if (attribute(key) < 0) continue;
            const std::string uv_at = at + "/attributes/" + key;
            const std::vector<double> uv = accessors_.read_accessor(
                attribute(key), TINYGLTF_TYPE_VEC2, 2,
                kPositionTypes, uv_at, n);
            if (uv.size() != 2 * n) fail(uv_at, "has a count other than POSITION's");
            for (std::size_t i = 0; i < n; ++i) uvs->emplace_back(uv[2 * i], uv[2 * i + 1]);
        }
        if (attribute("COLOR_0") >= 0) {
            // RGB or RGBA (the alpha is not used), float or normalized unsigned integers.
            const int index = attribute("COLOR_0");
            const bool rgba = static_cast<std::size_t>(index) < m_.accessors.size() &&
                              m_.accessors[static_cast<std::size_t>(index)].type == TINYGLTF_TYPE_VEC4;
            const int width = rgba ? 4 : 3;
            const std::vector<double> c = accessors_.read_accessor(
                index, rgba ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, width,
                {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                at + "/attributes/COLOR_0", n);
            if (c.size() != static_cast<std::size_t>(width) * n)
                fail(at + "/attributes/COLOR_0", "has a count other than POSITION's");
            for (std::size_t i = 0; i < n; ++i) {
                glm::vec3 colour;
                for (int k = 0; k < 3; ++k) {
                    const double v = c[i * width + k];
                    if (!(v >= 0 && v <= 1))
                        fail(pointer("accessors", static_cast<std::size_t>(index)),
                             "element " + std::to_string(i) + ": colours must be between 0 and 1");
                    colour[k] = static_cast<float>(v);
                }
                mesh.colours.push_back(colour);
            }
        }
        if (attribute("TANGENT") >= 0) {
            const std::vector<double> t =
                accessors_.read_accessor(attribute("TANGENT"), TINYGLTF_TYPE_VEC4, 4,
                              kDirectionTypes, at + "/attributes/TANGENT", n);
            if (t.size() != 4 * n) fail(at + "/attributes/TANGENT", "has a count other than POSITION's");
            for (std::size_t i = 0; i < n; ++i) {
                const glm::dvec3 v(t[4 * i], t[4 * i + 1], t[4 * i + 2]);
                // A tangent that is not finite drops them all: each triangle's own frame stands in.
                if (!std::isfinite(glm::length(v))) {
                    mesh.tangents.clear();
                    break;
                }
                mesh.tangents.emplace_back(glm::vec3(v), t[4 * i + 3] < 0 ? -1.0f : 1.0f);
            }
        }
        std::vector<std::uint32_t> corners;
        if (p.indices >= 0) {
            const std::string indices_at = pointer("accessors", static_cast<std::size_t>(p.indices));
            const std::vector<double> indices = accessors_.read_accessor(
                p.indices, TINYGLTF_TYPE_SCALAR, 1,
                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                at + "/indices", 3 * kMaxMeshTriangles);
            for (std::size_t k = 0; k < indices.size(); ++k) {
                if (indices[k] >= static_cast<double>(n))
                    fail(indices_at, "index " + std::to_string(k) + " is " +
                                         std::to_string(static_cast<std::uint64_t>(indices[k])) +
                                         ", beyond the " + std::to_string(n) + " vertices");
                corners.push_back(static_cast<std::uint32_t>(indices[k]));
            }
            mesh_places_.back().indices = p.indices;
        } else {
            for (std::size_t i = 0; i < n; ++i) corners.push_back(static_cast<std::uint32_t>(i));
        }
        // Strips and fans become the triangles they stand for, each counter-clockwise.
        const std::size_t c = corners.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (c % 3 != 0)
                fail(p.indices >= 0 ? at + "/indices" : positions_at,
                     std::to_string(c) + " corners do not make whole triangles");
            for (std::size_t k = 0; k < c; k += 3)
                mesh.triangles.push_back({corners[k], corners[k + 1], corners[k + 2]});
        } else {
            for (std::size_t k = 2; k < c; ++k) {
                if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
                    mesh.triangles.push_back({corners[0], corners[k - 1], corners[k]});
                else if (k % 2 == 0)
                    mesh.triangles.push_back({corners[k - 2], corners[k - 1], corners[k]});
                else
                    mesh.triangles.push_back({corners[k - 1], corners[k - 2], corners[k]});
            }
        }
        if (mesh.triangles.empty()) fail(at, "makes no triangle");
        return mesh;
    }

    // ---- skins and morph targets -----------------------------------------------------------

    // The morph targets of glTF mesh `index` (its primitives have as many: check_targets).
    std::size_t morph_targets(int index) const {
        return morph_target_count(m_.meshes[static_cast<std::size_t>(index)]);
    }

    // Every primitive of a mesh has as many morph targets, and its `weights` one a target.
    void check_targets(const tinygltf::Mesh& mesh, const std::string& at) const {
        const std::size_t n = morph_target_count(mesh);
        for (std::size_t p = 1; p < mesh.primitives.size(); ++p)
            if (mesh.primitives[p].targets.size() != n)
                fail(at + "/primitives/" + std::to_string(p) + "/targets",
                     std::to_string(mesh.primitives[p].targets.size()) +
                         " morph targets, where primitive 0 has " + std::to_string(n) +
                         " (a mesh's primitives have as many)");
        if (!mesh.weights.empty() && mesh.weights.size() != n)
            fail(at + "/weights", std::to_string(mesh.weights.size()) + " weights for " +
                                      std::to_string(n) + " morph targets");
    }

    // Where the model has skins or morph targets, the motion that poses them: the animation
    // asked for, or one without channels that poses them at rest.
    void prepare_deformation() {
        bool any = !m_.skins.empty();
        for (const tinygltf::Mesh& mesh : m_.meshes)
            for (const tinygltf::Primitive& p : mesh.primitives) any |= !p.targets.empty();
        if (!any) return;
        if (!motion_) {
            motion_ = std::make_shared<GltfMotion>();
            motion_->nodes.resize(m_.nodes.size());
            motion_->channels_of.resize(m_.nodes.size());
        }
        motion_->rest_weights.resize(m_.nodes.size());
    }

    // Skin `index` as the motion holds it: read on first use.
    std::size_t skin(int index, const std::string& use) {
        if (index < 0 || static_cast<std::size_t>(index) >= m_.skins.size())
            fail(use, "no skin " + std::to_string(index));
        if (const auto it = skins_.find(index); it != skins_.end()) return it->second;
        motion_->skins.push_back(read_skin(m_, index, accessors_));
        return skins_.emplace(index, motion_->skins.size() - 1).first->second;
    }

    // Node k's primitives, each a glint mesh of its own that its skin or morph targets move.
    std::vector<Part> deformable_parts(std::size_t k) {
        const tinygltf::Node& n = m_.nodes[k];
        const std::string at = pointer("nodes", k);
        const auto m = static_cast<std::size_t>(n.mesh);
        const tinygltf::Mesh& mesh = m_.meshes[m];
        check_targets(mesh, pointer("meshes", m));
        std::optional<std::size_t> skin_index, joints;
        if (n.skin >= 0) {
            skin_index = skin(n.skin, at + "/skin");
            joints = motion_->skins[*skin_index].joints.size();
        }
        const std::size_t targets = morph_targets(n.mesh);
        if (!n.weights.empty() && n.weights.size() != targets)
            fail(at + "/weights", std::to_string(n.weights.size()) + " weights for the " +
                                      std::to_string(targets) + " morph targets of its mesh");
        std::vector<double> weights = n.weights.empty() ? mesh.weights : n.weights;
        weights.resize(targets, 0.0);
        for (std::size_t i = 0; i < weights.size(); ++i)
            if (!(std::abs(weights[i]) <= kMaxCoordinate))
                fail(n.weights.empty() ? pointer("meshes", m) + "/weights" : at + "/weights",
                     "weight " + std::to_string(i) + " must be finite and within ±1e15");
        motion_->rest_weights[k] = std::move(weights);
        const UnusedFeature skip = [this](const std::string& feature, const std::string& place) {
            unused(feature, place);
        };
        std::vector<Part> parts;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::string p_at = pointer("meshes", m) + "/primitives/" + std::to_string(p);
            std::optional<TriangleMesh> triangles = primitive(mesh.primitives[p], p_at);
            if (!triangles) continue;
            Deformable d = read_deformable(mesh.primitives[p], p_at, *triangles, joints,
                                           accessors_, skip, renormalized_);
            d.mesh = static_cast<std::uint32_t>(scene_.meshes.size());
            d.node = k;
            d.skin = skin_index;
            parts.push_back({d.mesh, primitive_material(mesh.primitives[p], p_at)});
            scene_.meshes.push_back(std::move(*triangles));
            motion_->deformables.push_back(std::move(d));
        }
        return parts;
    }

    // ---- animation -------------------------------------------------------------------------

    // The chosen animation (io/gltf_animation.h), or a note where the file has none.
    void read_animation() {
        const int count = static_cast<int>(m_.animations.size());
        const int k = options_.animation;
        if (count == 0 && k == 0) {
            if (!options_.quiet_without_animation)
                scene_.notes.push_back("the file has no animations: --time places nothing");
            return;
        }
        if (k < 0 || k >= count)
            throw SceneError(name_ + ": --animation " + std::to_string(k) + ": the file has " +
                             (count == 0 ? "no animations"
                                         : std::to_string(count) + " animation(s), 0 to " +
                                               std::to_string(count - 1)));
        motion_ = read_gltf_animation(m_, k, accessors_, [this](const std::string& feature,
                                                                const std::string& place) {
            unused(feature, place);
        });
        motion_->animated = true;
    }

    // ---- nodes -----------------------------------------------------------------------------

    static DMat4 local_matrix(const tinygltf::Node& n, const std::string& at,
                              const std::function<void(const std::string&, const std::string&)>& fail) {
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) fail(at + "/matrix", "must have 16 numbers");
            DMat4 m;
            for (int c = 0; c < 4; ++c) // column-major, as glm
                for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[static_cast<std::size_t>(4 * c + r)];
            return m;
        }
        if (!n.translation.empty() && n.translation.size() != 3)
            fail(at + "/translation", "must have 3 numbers");
        if (!n.rotation.empty()) {
            if (n.rotation.size() != 4) fail(at + "/rotation", "must have 4 numbers (x, y, z, w)");
            const double length = glm::length(
                glm::dvec4(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]));
            if (!(length > 0) || !std::isfinite(length))
                fail(at + "/rotation", "must be a unit quaternion");
        }
        if (!n.scale.empty() && n.scale.size() != 3) fail(at + "/scale", "must have 3 numbers");
        return trs_matrix(node_trs(n));
    }

    struct Placed {
        std::size_t node;
        DMat4 world;
    };

    // The default scene's node trees, walked without recursion: each node's world matrix is its
    // parent's times its own. A node met twice is a cycle or a second parent: an error either way.
    void walk_nodes() {
        std::vector<int> roots;
        std::string roots_at;
        int chosen = m_.defaultScene;
        if (chosen >= 0 && static_cast<std::size_t>(chosen) >= m_.scenes.size())
            fail("/scene", "no scene " + std::to_string(chosen));
        if (chosen < 0 && !m_.scenes.empty()) chosen = 0;
        if (chosen >= 0) {
            roots = m_.scenes[static_cast<std::size_t>(chosen)].nodes;
            roots_at = pointer("scenes", static_cast<std::size_t>(chosen)) + "/nodes";
        } else { // no scene: every node that is no node's child
            std::vector<bool> child(m_.nodes.size(), false);
            for (const tinygltf::Node& n : m_.nodes)
                for (const int c : n.children)
                    if (c >= 0 && static_cast<std::size_t>(c) < child.size())
                        child[static_cast<std::size_t>(c)] = true;
            for (std::size_t i = 0; i < child.size(); ++i)
                if (!child[i]) roots.push_back(static_cast<int>(i));
            roots_at = "/nodes";
            scene_.notes.push_back("no scene given: every root node is drawn");
        }
        enum : std::uint8_t { unseen, open, done };
        std::vector<std::uint8_t> state(m_.nodes.size(), unseen);
        struct Frame {
            std::size_t node;
            DMat4 world;
            DMat4 rest; // the world matrix without the animation: the nodes as the file places them
            std::size_t next_child = 0;
        };
        const auto failing = [this](const std::string& at, const std::string& what) { fail(at, what); };
        const auto enter = [&](int node, const std::string& at, const DMat4& parent,
                               const DMat4& parent_rest, std::vector<Frame>& stack,
                               const std::string& parent_node) {
            if (node < 0 || static_cast<std::size_t>(node) >= m_.nodes.size())
                fail(at, "no node " + std::to_string(node));
            const auto k = static_cast<std::size_t>(node);
            if (state[k] == open)
                fail(at, "node " + std::to_string(node) + " is an ancestor of " + parent_node +
                             ": the node graph has a cycle");
            if (state[k] == done)
                fail(at, "node " + std::to_string(node) + " is placed a second time (a node has "
                                                          "at most one parent)");
            state[k] = open;
            DMat4 local = local_matrix(m_.nodes[k], pointer("nodes", k), failing);
            const DMat4 rest = parent_rest * local;
            if (motion_) {
                GltfMotion::Node& n = motion_->nodes[k];
                n.has_matrix = m_.nodes[k].matrix.size() == 16;
                n.matrix = local;
                n.trs = node_trs(m_.nodes[k]);
                for (const int child : m_.nodes[k].children)
                    n.children.push_back(static_cast<std::size_t>(child));
                if (motion_->moves(k)) local = motion_->local(k, *options_.time);
            }
            const DMat4 world = parent * local;
            place(k, world, rest);
            stack.push_back({k, world, rest});
        };
        for (std::size_t r = 0; r < roots.size(); ++r) {
            if (motion_ && roots[r] >= 0) motion_->roots.push_back(static_cast<std::size_t>(roots[r]));
            std::vector<Frame> stack;
            enter(roots[r], roots_at + "/" + std::to_string(r), DMat4(1.0), DMat4(1.0), stack,
                  "the scene");
            while (!stack.empty()) {
                Frame& top = stack.back();
                const tinygltf::Node& n = m_.nodes[top.node];
                if (top.next_child == n.children.size()) {
                    state[top.node] = done;
                    stack.pop_back();
                    continue;
                }
                const std::size_t j = top.next_child++;
                const DMat4 world = top.world, rest = top.rest; // `top` moves as the stack grows
                const std::string parent = "node " + std::to_string(top.node);
                enter(n.children[j], pointer("nodes", top.node) + "/children/" + std::to_string(j),
                      world, rest, stack, parent);
            }
        }
    }

    // What node k places: its mesh's primitives as objects, its camera, its light. `rest`: its
    // world matrix without the animation.
    void place(std::size_t k, const DMat4& world, const DMat4& rest) {
        const tinygltf::Node& n = m_.nodes[k];
        const std::string at = pointer("nodes", k);
        if (n.mesh >= 0) {
            if (static_cast<std::size_t>(n.mesh) >= m_.meshes.size())
                fail(at + "/mesh", "no mesh " + std::to_string(n.mesh));
            // A skinned mesh is posed in world space: the node's own matrix does not place it.
            const bool skinned = n.skin >= 0;
            const std::vector<Part> parts = skinned || morph_targets(n.mesh) > 0
                                                ? deformable_parts(k)
                                                : mesh(n.mesh, at + "/mesh");
            // EXT_mesh_gpu_instancing: every instance one more object over the same meshes.
            std::vector<DMat4> instances = read_instances(n, at, accessors_, kMaxModelObjects);
            if (skinned && !instances.empty()) {
                unused("instances of a skinned mesh (drawn once, posed by its skin)",
                       at + "/extensions/EXT_mesh_gpu_instancing");
                instances.clear();
            }
            const std::size_t copies = std::max<std::size_t>(instances.size(), 1);
            if (scene_.objects.size() + parts.size() * copies > kMaxModelObjects)
                fail(at, "the model places more than " + std::to_string(kMaxModelObjects) +
                             " objects");
            if (motion_ && !instances.empty() && motion_->object_offsets.empty())
                motion_->object_offsets.assign(scene_.objects.size(), DMat4(1.0));
            const std::string name =
                printable(n.name.empty() ? m_.meshes[static_cast<std::size_t>(n.mesh)].name : n.name);
            for (std::size_t c = 0; c < copies; ++c) {
                const DMat4 instance = instances.empty() ? DMat4(1.0) : instances[c];
                for (const Part& part : parts) {
                    SceneObject o;
                    o.shape = ShapeKind::mesh;
                    o.mesh = part.mesh;
                    o.material = part.material;
                    o.transform = skinned ? DMat4(1.0) : world * instance;
                    scene_.objects.push_back(o);
                    rest_transforms_.push_back(skinned ? DMat4(1.0) : rest * instance);
                    if (motion_) {
                        motion_->object_nodes.push_back(skinned ? GltfMotion::kNoNode : k);
                        if (!motion_->object_offsets.empty())
                            motion_->object_offsets.push_back(instance);
                    }
                    scene_.object_names.push_back(name);
                    object_places_.push_back(at);
                }
            }
        }
        if (n.camera >= 0) {
            if (static_cast<std::size_t>(n.camera) >= m_.cameras.size())
                fail(at + "/camera", "no camera " + std::to_string(n.camera));
            cameras_.emplace(n.camera, Placed{k, world}); // the first node placing it
        }
        if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
            const tinygltf::Value& light = it->second.Get("light");
            if (!light.IsInt() || light.GetNumberAsInt() < 0 ||
                static_cast<std::size_t>(light.GetNumberAsInt()) >= m_.lights.size())
                fail(at + "/extensions/KHR_lights_punctual/light", "no such light");
            lights_.push_back({static_cast<std::size_t>(light.GetNumberAsInt()), world, k});
        }
    }

    // ---- camera and lights -----------------------------------------------------------------

    void camera() {
        std::optional<int> chosen = options_.camera;
        if (chosen) {
            const int n = static_cast<int>(m_.cameras.size());
            if (*chosen < 0 || *chosen >= n)
                throw SceneError(name_ + ": --camera " + std::to_string(*chosen) + ": the file has " +
                                 (n == 0 ? "no cameras" : std::to_string(n) + " camera(s), 0 to " +
                                                              std::to_string(n - 1)));
            const std::string at = pointer("cameras", static_cast<std::size_t>(*chosen));
            if (!cameras_.contains(*chosen))
                fail(at, "--camera " + std::to_string(*chosen) +
                             ": no node of the scene places this camera");
            if (m_.cameras[static_cast<std::size_t>(*chosen)].type != "perspective")
                fail(at + "/type", "--camera " + std::to_string(*chosen) +
                                       ": glint's camera is a perspective (pinhole) one");
        } else {
            for (const auto& [index, placed] : cameras_) { // the first, in /cameras order
                if (m_.cameras[static_cast<std::size_t>(index)].type == "perspective") {
                    chosen = index;
                    break;
                }
                unused("orthographic cameras", pointer("cameras", static_cast<std::size_t>(index)));
            }
        }
        if (!chosen) {
            frame_model(scene_, options_.view.value_or(ModelView::front));
            camera_place_ = "the framing camera";
            return;
        }
        const Placed& placed = cameras_.at(*chosen);
        const tinygltf::Camera& c = m_.cameras[static_cast<std::size_t>(*chosen)];
        camera_place_ = pointer("cameras", static_cast<std::size_t>(*chosen));
        place_camera(scene_.camera, placed.world);
        if (motion_) motion_->camera_node = placed.node;
        scene_.camera.fov_y = c.perspective.yfov * (180.0 / std::numbers::pi);
        camera_place_node_ = pointer("nodes", placed.node);
    }

    void lights() {
        for (const PlacedLight& p : lights_) {
            const tinygltf::Light& l = m_.lights[p.light];
            const std::string at = "/extensions/KHR_lights_punctual/lights/" + std::to_string(p.light);
            glm::dvec3 colour(1.0);
            if (!l.color.empty()) {
                if (l.color.size() != 3) fail(at + "/color", "must have 3 numbers");
                colour = {l.color[0], l.color[1], l.color[2]};
            }
            if (!(l.intensity >= 0)) fail(at + "/intensity", "must not be negative");
            PointLight light{DVec3(p.world * glm::dvec4(0, 0, 0, 1)), glm::vec3(colour * l.intensity)};
            if (l.type == "spot") {
                unused("spot cones (spot lights shine as point lights)", at);
            } else if (l.type == "directional") {
                // A point light far along the direction it comes from: 100 radii from the model.
                unused("directional lights (placed as point lights 100 model radii away)", at);
                DVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
                UnitBoxes unit_boxes(scene_.meshes);
                for (const SceneObject& o : scene_.objects)
                    if (const std::optional<ObjectBox> box = unit_boxes(o)) {
                        const auto [a, b] = transformed_box(*box, o.transform);
                        lo = glm::min(lo, a), hi = glm::max(hi, b);
                    }
                const DVec3 centre = lo.x <= hi.x ? 0.5 * (lo + hi) : DVec3(0.0);
                const double radius = lo.x <= hi.x ? std::max(0.5 * glm::length(hi - lo), 1e-3) : 1;
                DVec3 d = DVec3(p.world * glm::dvec4(0, 0, -1, 0));
                if (!(glm::length(d) > 0)) fail(pointer("nodes", p.node), "a directional light's node must not scale it to nothing");
                light.position = centre - 100 * radius * glm::normalize(d);
            } else if (l.type != "point") {
                fail(at + "/type", "unknown light type '" + printable(l.type) + "'");
            }
            scene_.lights.push_back(light);
            // A directional light stands far off along its direction: it does not follow.
            if (motion_)
                motion_->light_nodes.push_back(l.type == "directional" ? GltfMotion::kNoNode : p.node);
            light_places_.push_back(at);
        }
        if (lights_.empty()) {
            // From the model's centre as the file places it, before any animation: a sequence's
            // frames and `--time` alone light the model alike.
            std::vector<SceneObject> at_rest = scene_.objects;
            for (std::size_t i = 0; i < at_rest.size(); ++i)
                at_rest[i].transform = rest_transforms_[i];
            // Skins and morph targets are posed at rest for it and then at the time again: a pose
            // rewrites every vertex it moves from the file's, so no copy of the meshes is needed.
            const bool deformed = motion_ && motion_->animated && !motion_->deformables.empty();
            if (deformed) motion_->deform(scene_.meshes, motion_->world(std::nullopt), std::nullopt);
            const std::optional<ModelSphere> sphere = model_sphere(at_rest, scene_.meshes);
            if (deformed) motion_->deform(scene_.meshes, motion_->world(options_.time), options_.time);
            light_model(scene_, sphere ? std::optional(sphere->centre) : std::nullopt);
            light_places_.assign(scene_.lights.size(), "the default lights");
        }
    }

    // ---- places ----------------------------------------------------------------------------

    std::string place_of(const std::string& path) const {
        const std::vector<std::string> parts = path_parts(path);
        const auto index = [&](std::size_t k) { return std::stoul(parts.at(k)); };
        const std::string& head = parts[0];
        std::string place;
        if (head == "materials" && parts.size() > 1) {
            place = materials_.place(index(1));
            if (parts.size() > 2 && parts[2] == "ior")
                place += "/extensions/KHR_materials_ior/ior";
        } else if (head == "objects" && parts.size() > 1) {
            place = object_places_.at(index(1)) + (parts.size() > 2 ? " (its world matrix)" : "");
        } else if (head == "meshes" && parts.size() > 2) {
            const MeshPlace& m = mesh_places_.at(index(1));
            if (parts[2] == "indices" && m.indices >= 0)
                place = pointer("accessors", static_cast<std::size_t>(m.indices));
            else
                place = m.positions;
            if (parts.size() > 3) place += ", element " + parts[3];
        } else if (head == "camera") {
            place = camera_place_ + (camera_place_node_.empty() ? "" : " on " + camera_place_node_);
        } else if (head == "lights" && parts.size() > 1) {
            place = light_places_.at(index(1));
        } else {
            place = "/" + path;
        }
        return name_ + ": " + place;
    }

    struct MeshPlace {
        std::string positions; // the POSITION accessor
        int indices;           // the indices accessor, or −1
    };
    struct PlacedLight {
        std::size_t light;
        DMat4 world;
        std::size_t node;
    };

    const tinygltf::Model& m_;
    const std::string& name_;
    const ModelOptions& options_;
    const GltfAccessors accessors_;
    Scene scene_;
    GltfMaterials materials_; // after scene_, which it adds to
    std::map<int, std::vector<Part>> meshes_;
    std::map<int, Placed> cameras_; // by camera index: ordered, so the first is /cameras' first
    std::vector<PlacedLight> lights_;
    std::map<std::string, std::string> unused_;
    std::vector<std::string> object_places_, light_places_;
    std::vector<MeshPlace> mesh_places_;
    std::vector<DMat4> rest_transforms_; // each object's world matrix without the animation
    // The animation asked for (options_.time), or the rest pose of skins and morph targets, or
    // none.
    std::shared_ptr<GltfMotion> motion_;
    std::map<int, std::size_t> skins_; // glTF skin → its index in motion_->skins
    std::string renormalized_;         // where skin weights were first renormalized
    std::string camera_place_, camera_place_node_;
};

} // namespace

Scene parse_gltf(const std::string& bytes, const std::string& name, const ModelFiles& files,
                 const ModelOptions& options) {
    std::vector<std::string> warnings;
    tinygltf::Model model = read_gltf_container(bytes, name, files, warnings);
    decode_meshopt(model, name);
    decode_draco(model, name);
    return Reader(model, name, files, options, std::move(warnings)).read();
}

Scene load_gltf(const std::filesystem::path& path, const ModelOptions& options) {
    const std::string bytes = read_scene_file(path, "glTF file");
    const std::filesystem::path dir = path.parent_path();
    const ModelFiles files = [&](const std::string& uri, std::string& why) {
        try {
            return std::optional<std::string>(read_scene_file(dir / uri, "file"));
        } catch (const SceneError& e) {
            why = e.what();
            return std::optional<std::string>();
        }
    };
    return parse_gltf(bytes, path.string(), files, options);
}

} // namespace glint
