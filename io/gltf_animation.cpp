#include "io/gltf_animation.h"

#include "io/gltf_accessors.h"
#include "io/read_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint {

namespace {

glm::dvec4 key(const KeyFrames& keys, std::size_t k, int element) {
    const int per_key = keys.interpolation == Interpolation::cubic_spline ? 3 : 1;
    const std::size_t at = (k * per_key + element) * keys.width;
    glm::dvec4 v(0.0);
    for (int c = 0; c < keys.width; ++c) v[c] = keys.values[at + c];
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

} // namespace

glm::dvec4 sample_keys(const KeyFrames& keys, double t, bool rotation) {
    const std::vector<double>& times = keys.times;
    const int value = keys.interpolation == Interpolation::cubic_spline ? 1 : 0;
    const auto unit = [&](glm::dvec4 v) { return rotation ? glm::normalize(v) : v; };
    if (!(t > times.front())) return unit(key(keys, 0, value));
    if (t >= times.back()) return unit(key(keys, times.size() - 1, value));
    // The key interval [t_k, t_k+1) that holds t.
    const std::size_t k =
        static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const double span = times[k + 1] - times[k];
    const double s = (t - times[k]) / span;
    switch (keys.interpolation) {
    case Interpolation::step: return unit(key(keys, k, 0));
    case Interpolation::linear:
        return rotation ? slerp(key(keys, k, 0), key(keys, k + 1, 0), s)
                        : glm::mix(key(keys, k, 0), key(keys, k + 1, 0), s);
    case Interpolation::cubic_spline: {
        const glm::dvec4 p0 = key(keys, k, 1), m0 = span * key(keys, k, 2);
        const glm::dvec4 p1 = key(keys, k + 1, 1), m1 = span * key(keys, k + 1, 0);
        const double s2 = s * s, s3 = s2 * s;
        return unit((2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 +
                    (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1);
    }
    }
    return {};
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

DMat4 GltfMotion::local(std::size_t k, double t) const {
    const Node& n = nodes[k];
    if (!moves(k)) return n.has_matrix ? n.matrix : trs_matrix(n.trs);
    NodeTrs trs = n.trs;
    for (const std::size_t index : channels_of[k]) {
        const Channel& c = channels[index];
        const glm::dvec4 v = sample_keys(samplers[c.keys], t, c.path == TrsPath::rotation);
        switch (c.path) {
        case TrsPath::translation: trs.translation = DVec3(v); break;
        case TrsPath::rotation: trs.rotation = v; break;
        case TrsPath::scale: trs.scale = DVec3(v); break;
        }
    }
    return trs_matrix(trs);
}

std::vector<DMat4> GltfMotion::world(double t) const {
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

void GltfMotion::pose(Scene& scene, double t) const {
    const std::vector<DMat4> at = world(t);
    for (std::size_t i = 0; i < object_nodes.size() && i < scene.objects.size(); ++i)
        scene.objects[i].transform = at[object_nodes[i]];
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
            else if (c.target_path == "weights") {
                unused_("morph target weights (animation channels)", channel_at);
                continue;
            } else {
                accessors_.fail(channel_at + "/target/path",
                     "must be translation, rotation, scale or weights, not '" +
                         printable(c.target_path) + "'");
            }
            if (c.sampler < 0 || static_cast<std::size_t>(c.sampler) >= a.samplers.size())
                accessors_.fail(channel_at + "/sampler", "no sampler " + std::to_string(c.sampler));
            if (!m_.nodes[static_cast<std::size_t>(c.target_node)].matrix.empty())
                accessors_.fail(pointer("nodes", static_cast<std::size_t>(c.target_node)) + "/matrix",
                     "an animated node must be placed by translation, rotation and scale, not "
                     "a matrix (" + channel_at + " moves it)");
            motion->samplers.push_back(keys(a.samplers[static_cast<std::size_t>(c.sampler)],
                                            at + "/samplers/" + std::to_string(c.sampler), path));
            motion->channels_of[static_cast<std::size_t>(c.target_node)].push_back(
                motion->channels.size());
            motion->channels.push_back({static_cast<std::size_t>(c.target_node), path,
                                        motion->samplers.size() - 1});
        }
        return motion;
    }

  private:
// A sampler's keys for a channel of `path`: times strictly increasing, outputs of the path's
// type, one (three for CUBICSPLINE) a key.
KeyFrames keys(const tinygltf::AnimationSampler& s, const std::string& at, TrsPath path) const {
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
    out.width = rotation ? 4 : 3;
    const std::size_t per_key = out.interpolation == Interpolation::cubic_spline ? 3 : 1;
    const std::size_t wanted = out.times.size() * per_key;
    const std::string use = at + "/output";
    out.values = rotation
                     ? accessors_.read_accessor(s.output, TINYGLTF_TYPE_VEC4, 4,
                                     {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                      TINYGLTF_COMPONENT_TYPE_SHORT,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                     use, kMaxAnimationKeys * 3)
                     : accessors_.read_accessor(s.output, TINYGLTF_TYPE_VEC3, 3,
                                     {TINYGLTF_COMPONENT_TYPE_FLOAT}, use,
                                     kMaxAnimationKeys * 3);
    const std::string output_at = pointer("accessors", static_cast<std::size_t>(s.output));
    const std::size_t count = out.values.size() / static_cast<std::size_t>(out.width);
    if (count != wanted)
        accessors_.fail(output_at + "/count",
             std::to_string(count) + " elements, where the sampler's " +
                 std::to_string(out.times.size()) + " keys need " + std::to_string(wanted) +
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
