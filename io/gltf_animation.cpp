#include "io/gltf_animation.h"

#include "io/gltf_accessors.h"
#include "io/read_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint {

namespace {

// Component c of key k's element (0 in-tangent or value, 1 value, 2 out-tangent).
double component(const KeyFrames& keys, std::size_t k, int element, int c) {
    const int per_key = keys.interpolation == Interpolation::cubic_spline ? 3 : 1;
    return keys.values[(k * per_key + element) * keys.width + c];
}

glm::dvec4 key(const KeyFrames& keys, std::size_t k, int element) {
    glm::dvec4 v(0.0);
    for (int c = 0; c < keys.width; ++c) v[c] = component(keys, k, element, c);
    return v;
}

// The specification's slerp (Appendix C): along the shorter arc, linear where the two are
// (nearly) one rotation.
glm::dvec4 slerp(glm::dvec4 a, glm::dvec4 b, double s) {
    const double d = glm::dot(a, b);
    const double angle = std::acos(std::min(std::abs(d), 1.0));
    const double sign = d < 0 ? -1.0 : 1.0;
    if (angle < 1e-9) return glm::normalize(glm::mix(a, sign * b, s));
    return (std::sin(angle * (1 - s)) * a + sign * std::sin(angle * s) * b) / std::sin(angle);
}

// Where t falls among the keys: before the first (k = 0, s = 0, held), after the last (the last
// key, held), or in the interval [t_k, t_k+1) at fraction s.
struct KeyPlace {
    std::size_t k = 0;
    double s = 0, span = 0;
    bool held = true;
};

KeyPlace locate(const std::vector<double>& times, double t) {
    if (!(t > times.front())) return {};
    if (t >= times.back()) return {times.size() - 1, 0, 0, true};
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double span = times[k + 1] - times[k];
    return {k, (t - times[k]) / span, span, false};
}

// Component c at `at`, interpolated as a translation is (STEP, LINEAR, CUBICSPLINE's Hermite).
double interpolate(const KeyFrames& keys, const KeyPlace& at, int c) {
    const int value = keys.interpolation == Interpolation::cubic_spline ? 1 : 0;
    if (at.held || keys.interpolation == Interpolation::step) return component(keys, at.k, value, c);
    if (keys.interpolation == Interpolation::linear)
        return (1 - at.s) * component(keys, at.k, 0, c) + at.s * component(keys, at.k + 1, 0, c);
    const double p0 = component(keys, at.k, 1, c), m0 = at.span * component(keys, at.k, 2, c);
    const double p1 = component(keys, at.k + 1, 1, c), m1 = at.span * component(keys, at.k + 1, 0, c);
    const double s = at.s, s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 +
           (s3 - s2) * m1;
}

} // namespace

glm::dvec4 sample_keys(const KeyFrames& keys, double t, bool rotation) {
    const KeyPlace at = locate(keys.times, t);
    glm::dvec4 v(0.0);
    if (rotation && !at.held && keys.interpolation == Interpolation::linear)
        return slerp(key(keys, at.k, 0), key(keys, at.k + 1, 0), at.s);
    for (int c = 0; c < keys.width; ++c) v[c] = interpolate(keys, at, c);
    return rotation ? glm::normalize(v) : v;
}

std::vector<double> sample_weights(const KeyFrames& keys, double t) {
    const KeyPlace at = locate(keys.times, t);
    std::vector<double> out(static_cast<std::size_t>(keys.width));
    for (int c = 0; c < keys.width; ++c) out[static_cast<std::size_t>(c)] = interpolate(keys, at, c);
    return out;
}

DMat4 trs_matrix(const NodeTrs& trs) {
    const glm::dvec4& q = trs.rotation;
    const double x = q.x, y = q.y, z = q.z, w = q.w;
    DMat4 r(1.0);
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0};
    r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0};
    r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0};
    return translation_matrix(trs.translation) * r * scale_matrix(trs.scale);
}

NodeTrs node_trs(const tinygltf::Node& n) {
    NodeTrs trs;
    if (n.translation.size() == 3)
        trs.translation = {n.translation[0], n.translation[1], n.translation[2]};
    if (n.rotation.size() == 4) {
        const glm::dvec4 q(n.rotation[0], n.rotation[1], n.rotation[2], n.rotation[3]);
        trs.rotation = q / glm::length(q);
    }
    if (n.scale.size() == 3) trs.scale = {n.scale[0], n.scale[1], n.scale[2]};
    return trs;
}

bool GltfMotion::moves(std::size_t k) const {
    return !channels_of[k].empty();
}

DMat4 GltfMotion::local(std::size_t k, std::optional<double> t) const {
    const Node& n = nodes[k];
    if (!t || !moves(k)) return n.has_matrix ? n.matrix : trs_matrix(n.trs);
    NodeTrs trs = n.trs;
    for (const std::size_t index : channels_of[k]) {
        const Channel& c = channels[index];
        const glm::dvec4 v = sample_keys(samplers[c.keys], *t, c.path == TrsPath::rotation);
        switch (c.path) {
        case TrsPath::translation: trs.translation = DVec3(v); break;
        case TrsPath::rotation: trs.rotation = v; break;
        case TrsPath::scale: trs.scale = DVec3(v); break;
        case TrsPath::weights: break; // not among `channels`
        }
    }
    return trs_matrix(trs);
}

std::vector<DMat4> GltfMotion::world(std::optional<double> t) const {
    std::vector<DMat4> out(nodes.size(), DMat4(1.0));
    // The loader has checked the graph: a forest, each node under one parent at most.
    std::vector<std::pair<std::size_t, DMat4>> stack;
    for (const std::size_t root : roots) stack.emplace_back(root, DMat4(1.0));
    while (!stack.empty()) {
        const auto [k, parent] = stack.back();
        stack.pop_back();
        out[k] = parent * local(k, t);
        for (const std::size_t child : nodes[k].children) stack.emplace_back(child, out[k]);
    }
    return out;
}

double GltfMotion::duration() const {
    double last = 0;
    for (const KeyFrames& keys : samplers) last = std::max(last, keys.times.back());
    return last;
}

std::vector<double> GltfMotion::weights(std::size_t k, std::optional<double> t) const {
    std::vector<double> w = rest_weights[k];
    if (t)
        for (const Channel& c : weight_channels)
            if (c.node == k) w = sample_weights(samplers[c.keys], *t);
    return w;
}

void GltfMotion::deform(std::vector<TriangleMesh>& meshes, const std::vector<DMat4>& at,
                        std::optional<double> t) const {
    std::vector<std::vector<DMat4>> joint_matrices(skins.size());
    for (std::size_t s = 0; s < skins.size(); ++s)
        for (std::size_t j = 0; j < skins[s].joints.size(); ++j)
            joint_matrices[s].push_back(at[skins[s].joints[j]] * skins[s].inverse_bind[j]);
    for (const Deformable& d : deformables) {
        const std::vector<double> morph = weights(d.node, t);
        glint::deform(d, morph, d.skin ? std::span<const DMat4>(joint_matrices[*d.skin])
                                       : std::span<const DMat4>(),
                      meshes[d.mesh]);
    }
}

std::vector<std::uint32_t> GltfMotion::moving_meshes() const {
    std::vector<std::uint32_t> out;
    for (const Deformable& d : deformables) out.push_back(d.mesh);
    return out;
}

void GltfMotion::pose(Scene& scene, double t) const {
    const std::vector<DMat4> at = world(t);
    for (std::size_t i = 0; i < object_nodes.size() && i < scene.objects.size(); ++i)
        if (object_nodes[i] != kNoNode)
            scene.objects[i].transform =
                object_offsets.empty() ? at[object_nodes[i]] : at[object_nodes[i]] * object_offsets[i];
    deform(scene.meshes, at, t);
    for (std::size_t i = 0; i < light_nodes.size() && i < scene.lights.size(); ++i)
        if (light_nodes[i] < at.size())
            scene.lights[i].position = DVec3(at[light_nodes[i]] * glm::dvec4(0, 0, 0, 1));
    if (camera_node) place_camera(scene.camera, at[*camera_node]);
}

void place_camera(Camera& camera, const DMat4& world) {
    camera.eye = DVec3(world * glm::dvec4(0, 0, 0, 1));
    camera.look_at = camera.eye + DVec3(world * glm::dvec4(0, 0, -1, 0));
    camera.up = DVec3(world * glm::dvec4(0, 1, 0, 0));
}

namespace {

// Keys an animation sampler may hold.
constexpr std::size_t kMaxAnimationKeys = std::size_t{1} << 22;

std::string seconds_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

class AnimationReader {
  public:
    AnimationReader(const tinygltf::Model& model, const GltfAccessors& accessors,
                    const UnusedFeature& unused)
        : m_(model), accessors_(accessors), unused_(unused) {}

    std::shared_ptr<GltfMotion> read(int index) const {
        const tinygltf::Animation& a = m_.animations[static_cast<std::size_t>(index)];
        const std::string at = pointer("animations", static_cast<std::size_t>(index));
        auto motion = std::make_shared<GltfMotion>();
        motion->label = "animation " + std::to_string(index) +
                        (a.name.empty() ? "" : " (" + printable(a.name) + ")");
        motion->nodes.resize(m_.nodes.size());
        motion->channels_of.resize(m_.nodes.size());
        for (std::size_t i = 0; i < a.channels.size(); ++i) {
            const tinygltf::AnimationChannel& c = a.channels[i];
            const std::string channel_at = at + "/channels/" + std::to_string(i);
            if (c.target_node < 0) {
                unused_("animation channels without a target node", channel_at);
                continue;
            }
            if (static_cast<std::size_t>(c.target_node) >= m_.nodes.size())
                accessors_.fail(channel_at + "/target/node", "no node " + std::to_string(c.target_node));
            TrsPath path;
            if (c.target_path == "translation") path = TrsPath::translation;
            else if (c.target_path == "rotation") path = TrsPath::rotation;
            else if (c.target_path == "scale") path = TrsPath::scale;
            else if (c.target_path == "weights") path = TrsPath::weights;
            else {
                accessors_.fail(channel_at + "/target/path",
                     "must be translation, rotation, scale or weights, not '" +
                         printable(c.target_path) + "'");
            }
            if (c.sampler < 0 || static_cast<std::size_t>(c.sampler) >= a.samplers.size())
                accessors_.fail(channel_at + "/sampler", "no sampler " + std::to_string(c.sampler));
            const auto node = static_cast<std::size_t>(c.target_node);
            const std::string sampler_at = at + "/samplers/" + std::to_string(c.sampler);
            if (path == TrsPath::weights) {
                const std::size_t targets = morph_targets(node);
                if (targets == 0)
                    accessors_.fail(channel_at + "/target/node",
                                    "node " + std::to_string(node) +
                                        " has no mesh with morph targets for weights to move");
                motion->samplers.push_back(keys(a.samplers[static_cast<std::size_t>(c.sampler)],
                                                sampler_at, path, targets));
                motion->weight_channels.push_back({node, path, motion->samplers.size() - 1});
                continue;
            }
            if (!m_.nodes[static_cast<std::size_t>(c.target_node)].matrix.empty())
                accessors_.fail(pointer("nodes", static_cast<std::size_t>(c.target_node)) + "/matrix",
                     "an animated node must be placed by translation, rotation and scale, not "
                     "a matrix (" + channel_at + " moves it)");
            motion->samplers.push_back(keys(a.samplers[static_cast<std::size_t>(c.sampler)],
                                            sampler_at, path));
            motion->channels_of[static_cast<std::size_t>(c.target_node)].push_back(
                motion->channels.size());
            motion->channels.push_back({static_cast<std::size_t>(c.target_node), path,
                                        motion->samplers.size() - 1});
        }
        return motion;
    }

  private:
// The morph targets of node k's mesh, or 0.
std::size_t morph_targets(std::size_t k) const {
    const int mesh = m_.nodes[k].mesh;
    if (mesh < 0 || static_cast<std::size_t>(mesh) >= m_.meshes.size()) return 0;
    return morph_target_count(m_.meshes[static_cast<std::size_t>(mesh)]);
}

// A sampler's keys for a channel of `path`: times strictly increasing, outputs of the path's
// type, one (three for CUBICSPLINE) a key; morph weights, `targets` scalars a key.
KeyFrames keys(const tinygltf::AnimationSampler& s, const std::string& at, TrsPath path,
               std::size_t targets = 0) const {
    KeyFrames out;
    if (s.interpolation.empty() || s.interpolation == "LINEAR")
        out.interpolation = Interpolation::linear;
    else if (s.interpolation == "STEP")
        out.interpolation = Interpolation::step;
    else if (s.interpolation == "CUBICSPLINE")
        out.interpolation = Interpolation::cubic_spline;
    else
        accessors_.fail(at + "/interpolation", "must be LINEAR, STEP or CUBICSPLINE, not '" +
                                        printable(s.interpolation) + "'");
    out.times = accessors_.read_accessor(s.input, TINYGLTF_TYPE_SCALAR, 1, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                              at + "/input", kMaxAnimationKeys);
    const std::string input_at = pointer("accessors", static_cast<std::size_t>(s.input));
    for (std::size_t k = 0; k < out.times.size(); ++k) {
        if (!std::isfinite(out.times[k]))
            accessors_.fail(input_at, "key time " + std::to_string(k) + " is not a finite number");
        if (k > 0 && !(out.times[k] > out.times[k - 1]))
            accessors_.fail(input_at, "key times must increase: key " + std::to_string(k) + " (" +
                               seconds_text(out.times[k]) + " s) does not come after key " +
                               std::to_string(k - 1) + " (" +
                               seconds_text(out.times[k - 1]) + " s)");
    }
    const bool rotation = path == TrsPath::rotation;
    out.width = rotation ? 4 : path == TrsPath::weights ? static_cast<int>(targets) : 3;
    const std::size_t per_key = out.interpolation == Interpolation::cubic_spline ? 3 : 1;
    const std::size_t wanted = out.times.size() * per_key;
    const std::string use = at + "/output";
    const std::initializer_list<int> quantized = {
        TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
        TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
    if (path == TrsPath::weights) {
        // Scalars, `targets` a key: read as one and regrouped by the width. At most as many
        // values as a VEC3 channel may hold elements, however many targets there are.
        out.values = accessors_.read_accessor(s.output, TINYGLTF_TYPE_SCALAR, 1, quantized, use,
                                              kMaxAnimationKeys * 3);
    } else {
        // Integer components: KHR_mesh_quantization's (rotations normalized, translations and
        // scales either).
        out.values = accessors_.read_accessor(s.output, rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                              out.width, quantized, use, kMaxAnimationKeys * 3);
    }
    const std::string output_at = pointer("accessors", static_cast<std::size_t>(s.output));
    const std::size_t count = out.values.size() / static_cast<std::size_t>(out.width);
    const bool scalars = path == TrsPath::weights; // one element a target
    if (out.values.size() != wanted * static_cast<std::size_t>(out.width))
        accessors_.fail(output_at + "/count",
             std::to_string(scalars ? out.values.size() : count) + " elements, where the sampler's " +
                 std::to_string(out.times.size()) + " keys need " +
                 std::to_string(scalars ? wanted * targets : wanted) +
                 (scalars ? " (one a morph target)" : "") +
                 (per_key == 3 ? " (CUBICSPLINE: in-tangent, value, out-tangent a key)" : ""));
    for (std::size_t i = 0; i < out.values.size(); ++i)
        if (!(std::abs(out.values[i]) <= kMaxCoordinate))
            accessors_.fail(output_at, "element " + std::to_string(i / out.width) +
                                ": values must be finite and within ±1e15");
    if (rotation)
        for (std::size_t k = 0; k < count; k += per_key) {
            const std::size_t v = (k + (per_key == 3 ? 1 : 0)) * 4;
            const glm::dvec4 q(out.values[v], out.values[v + 1], out.values[v + 2],
                               out.values[v + 3]);
            if (!(glm::length(q) > 0))
                accessors_.fail(output_at, "element " + std::to_string(k + (per_key == 3 ? 1 : 0)) +
                                    ": a rotation must be a unit quaternion");
        }
    return out;
}

    const tinygltf::Model& m_;
    const GltfAccessors& accessors_;
    const UnusedFeature& unused_;
};

} // namespace

std::shared_ptr<GltfMotion> read_gltf_animation(const tinygltf::Model& model, int index,
                                                const GltfAccessors& accessors,
                                                const UnusedFeature& unused) {
    return AnimationReader(model, accessors, unused).read(index);
}

} // namespace glint
