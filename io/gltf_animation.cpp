#include "io/gltf_animation.h"

#include <algorithm>
#include <cmath>

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
    const glm::dvec4 q = glm::normalize(trs.rotation);
    const double x = q.x, y = q.y, z = q.z, w = q.w;
    DMat4 r(1.0);
    r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0};
    r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0};
    r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0};
    return translation_matrix(trs.translation) * r * scale_matrix(trs.scale);
}

bool GltfMotion::moves(std::size_t k) const {
    return std::any_of(channels.begin(), channels.end(),
                       [&](const Channel& c) { return c.node == k; });
}

DMat4 GltfMotion::local(std::size_t k, double t) const {
    const Node& n = nodes[k];
    if (!moves(k)) return n.has_matrix ? n.matrix : trs_matrix(n.trs);
    NodeTrs trs = n.trs;
    for (const Channel& c : channels) {
        if (c.node != k) continue;
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

} // namespace glint
