#include "io/gltf_skin.h"

#include "io/error.h"
#include "io/gltf_accessors.h"
#include "io/gltf_container.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

// How far a vertex's weights may sum from 1 and be used as written: float rounding of four to
// eight weights is below 1e-6, and 16-bit normalized weights round each by 1/131070 at most.
// The specification asks for a sum "as close as reasonably possible to 1" and names no number.
constexpr double kWeightSumTolerance = 1e-4;

// Morph target values a primitive may hold (targets × vertices): one accessor named by many
// targets would otherwise make a small file fill the memory.
constexpr std::size_t kMaxMorphValues = std::size_t{1} << 24;

glm::dvec3 xyz(const std::vector<double>& v, std::size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

} // namespace

void deform(const Deformable& d, std::span<const double> morph,
            std::span<const DMat4> joint_matrices, TriangleMesh& mesh) {
    const std::size_t n = d.positions.size();
    for (std::size_t i = 0; i < n; ++i) {
        glm::dvec3 p = d.positions[i];
        glm::dvec3 normal = d.normals.empty() ? glm::dvec3(0) : d.normals[i];
        glm::dvec3 tangent = d.tangents.empty() ? glm::dvec3(0) : glm::dvec3(d.tangents[i]);
        for (std::size_t t = 0; t < d.targets.size() && t < morph.size(); ++t) {
            const Deformable::Target& target = d.targets[t];
            if (!target.positions.empty()) p += morph[t] * target.positions[i];
            if (!target.normals.empty()) normal += morph[t] * target.normals[i];
            if (!target.tangents.empty()) tangent += morph[t] * target.tangents[i];
        }
        if (d.skin) {
            DMat4 s(0.0);
            for (int k = 0; k < d.influences; ++k) {
                const std::size_t at = i * static_cast<std::size_t>(d.influences) + k;
                if (d.weights[at] != 0) s += d.weights[at] * joint_matrices[d.joints[at]];
            }
            p = glm::dvec3(s * glm::dvec4(p, 1.0));
            const glm::dmat3 linear(s);
            normal = glm::transpose(glm::inverse(linear)) * normal;
            tangent = linear * tangent;
        }
        mesh.vertices[i] = glm::vec3(p);
        if (!mesh.normals.empty()) {
            const double length = glm::length(normal);
            // Where a normal comes out zero or not finite, the facet's stands in (as on reading).
            mesh.normals[i] = length > 0 && std::isfinite(length) ? glm::vec3(normal / length)
                                                                  : glm::vec3(0);
        }
        if (!mesh.tangents.empty()) {
            const double length = glm::length(tangent);
            const glm::vec3 unit =
                length > 0 && std::isfinite(length) ? glm::vec3(tangent / length) : glm::vec3(0);
            mesh.tangents[i] = glm::vec4(unit, mesh.tangents[i].w);
        }
    }
}

std::size_t morph_target_count(const tinygltf::Mesh& mesh) {
    return mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
}

GltfSkin read_skin(const tinygltf::Model& model, int index, const GltfAccessors& accessors) {
    const tinygltf::Skin& s = model.skins[static_cast<std::size_t>(index)];
    const std::string at = pointer("skins", static_cast<std::size_t>(index));
    if (s.joints.empty()) accessors.fail(at + "/joints", "a skin needs at least one joint");
    GltfSkin skin;
    for (std::size_t j = 0; j < s.joints.size(); ++j) {
        if (s.joints[j] < 0 || static_cast<std::size_t>(s.joints[j]) >= model.nodes.size())
            accessors.fail(at + "/joints/" + std::to_string(j), "no node " + std::to_string(s.joints[j]));
        skin.joints.push_back(static_cast<std::size_t>(s.joints[j]));
    }
    if (s.inverseBindMatrices < 0) { // every inverse bind matrix the identity
        skin.inverse_bind.assign(skin.joints.size(), DMat4(1.0));
        return skin;
    }
    const std::string use = at + "/inverseBindMatrices";
    const std::vector<double> m =
        accessors.read_accessor(s.inverseBindMatrices, TINYGLTF_TYPE_MAT4, 16,
                                {TINYGLTF_COMPONENT_TYPE_FLOAT}, use, skin.joints.size());
    const std::string matrices_at = pointer("accessors", static_cast<std::size_t>(s.inverseBindMatrices));
    if (m.size() != 16 * skin.joints.size())
        accessors.fail(matrices_at + "/count", std::to_string(m.size() / 16) + " matrices for " +
                                                   std::to_string(skin.joints.size()) + " joints");
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        DMat4 matrix;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) {
                const double v = m[16 * j + 4 * c + r];
                if (!(std::abs(v) <= kMaxCoordinate))
                    accessors.fail(matrices_at, "element " + std::to_string(j) +
                                                    ": values must be finite and within ±1e15");
                matrix[c][r] = v;
            }
        skin.inverse_bind.push_back(matrix);
    }
    return skin;
}

Deformable read_deformable(const tinygltf::Primitive& p,
                           const std::string& at, const TriangleMesh& mesh,
                           std::optional<std::size_t> joint_count, const GltfAccessors& accessors,
                           const UnusedFeature& unused, std::string& renormalized) {
    Deformable d;
    const std::size_t n = mesh.vertices.size();
    for (const glm::vec3& v : mesh.vertices) d.positions.emplace_back(v);
    for (const glm::vec3& v : mesh.normals) d.normals.emplace_back(v);
    for (const glm::vec4& v : mesh.tangents) d.tangents.emplace_back(v);
    const auto vec3s = [&](int index, const std::string& use, bool quantized) {
        std::vector<double> v = accessors.read_accessor(
            index, TINYGLTF_TYPE_VEC3, 3,
            quantized ? std::initializer_list<int>{TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                   TINYGLTF_COMPONENT_TYPE_BYTE,
                                                   TINYGLTF_COMPONENT_TYPE_SHORT}
                      : std::initializer_list<int>{TINYGLTF_COMPONENT_TYPE_FLOAT},
            use, n);
        if (v.size() != 3 * n) accessors.fail(use, "has a count other than POSITION's");
        std::vector<glm::dvec3> out;
        for (std::size_t i = 0; i < n; ++i) {
            out.push_back(xyz(v, i));
            if (!(glm::length(out.back()) <= kMaxCoordinate))
                accessors.fail(pointer("accessors", static_cast<std::size_t>(index)),
                               "element " + std::to_string(i) +
                                   ": values must be finite and within ±1e15");
        }
        return out;
    };
    if (!p.targets.empty() && p.targets.size() > kMaxMorphValues / std::max<std::size_t>(n, 1))
        accessors.fail(at + "/targets", std::to_string(p.targets.size()) + " morph targets of " +
                                            std::to_string(n) + " vertices; the limit is " +
                                            std::to_string(kMaxMorphValues) + " values");
    for (std::size_t t = 0; t < p.targets.size(); ++t) {
        Deformable::Target target;
        const std::string target_at = at + "/targets/" + std::to_string(t);
        for (const auto& [key, index] : p.targets[t]) {
            const std::string use = target_at + "/" + key;
            if (key == "POSITION") target.positions = vec3s(index, use, true);
            else if (key == "NORMAL" && !d.normals.empty()) target.normals = vec3s(index, use, true);
            else if (key == "TANGENT" && !d.tangents.empty()) target.tangents = vec3s(index, use, true);
            else if (key != "NORMAL" && key != "TANGENT")
                unused("morph targets of " + printable(key), use);
        }
        d.targets.push_back(std::move(target));
    }
    if (!joint_count) return d;

    const auto attribute = [&](const std::string& key) {
        const auto it = p.attributes.find(key);
        return it == p.attributes.end() ? -1 : it->second;
    };
    if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0)
        accessors.fail(at + "/attributes", "a skinned mesh needs JOINTS_0 and WEIGHTS_0");
    d.skin = 0; // the caller sets which
    for (int set = 0; attribute("JOINTS_" + std::to_string(set)) >= 0; ++set) {
        const std::string joints_use = at + "/attributes/JOINTS_" + std::to_string(set);
        const std::string weights_use = at + "/attributes/WEIGHTS_" + std::to_string(set);
        if (attribute("WEIGHTS_" + std::to_string(set)) < 0)
            accessors.fail(at + "/attributes", "JOINTS_" + std::to_string(set) +
                                                   " needs WEIGHTS_" + std::to_string(set));
        const int joints_index = attribute("JOINTS_" + std::to_string(set));
        const std::vector<double> joints = accessors.read_accessor(
            joints_index, TINYGLTF_TYPE_VEC4, 4,
            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
            joints_use, n);
        const std::vector<double> weights = accessors.read_accessor(
            attribute("WEIGHTS_" + std::to_string(set)), TINYGLTF_TYPE_VEC4, 4,
            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
             TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
            weights_use, n);
        if (joints.size() != 4 * n) accessors.fail(joints_use, "has a count other than POSITION's");
        if (weights.size() != 4 * n) accessors.fail(weights_use, "has a count other than POSITION's");
        d.influences += 4;
        // Interleave the set into each vertex's influences: the first 4·set are the sets before.
        std::vector<std::uint32_t> all_joints(static_cast<std::size_t>(d.influences) * n);
        std::vector<double> all_weights(all_joints.size());
        const auto before = static_cast<std::size_t>(d.influences - 4);
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t k = 0; k < before; ++k) {
                all_joints[i * (before + 4) + k] = d.joints[i * before + k];
                all_weights[i * (before + 4) + k] = d.weights[i * before + k];
            }
            for (std::size_t k = 0; k < 4; ++k) {
                const double joint = joints[4 * i + k], weight = weights[4 * i + k];
                if (joint >= static_cast<double>(*joint_count))
                    accessors.fail(pointer("accessors", static_cast<std::size_t>(joints_index)),
                                   "element " + std::to_string(i) + ": joint " +
                                       std::to_string(static_cast<std::uint64_t>(joint)) +
                                       " is beyond the skin's " + std::to_string(*joint_count) +
                                       " joints");
                if (!(weight >= 0) || !std::isfinite(weight))
                    accessors.fail(weights_use, "element " + std::to_string(i) +
                                                    ": weights must be finite and not negative");
                all_joints[i * (before + 4) + before + k] = static_cast<std::uint32_t>(joint);
                all_weights[i * (before + 4) + before + k] = weight;
            }
        }
        d.joints = std::move(all_joints);
        d.weights = std::move(all_weights);
    }
    const auto m = static_cast<std::size_t>(d.influences);
    for (std::size_t i = 0; i < n; ++i) {
        double sum = 0;
        for (std::size_t k = 0; k < m; ++k) sum += d.weights[i * m + k];
        if (!(sum > 0))
            accessors.fail(at + "/attributes/WEIGHTS_0",
                           "vertex " + std::to_string(i) + ": its weights are all zero");
        if (std::abs(sum - 1) <= kWeightSumTolerance) continue;
        if (renormalized.empty())
            renormalized = at + "/attributes/WEIGHTS_0, vertex " + std::to_string(i) +
                           " (sum " + std::to_string(sum) + ")";
        for (std::size_t k = 0; k < m; ++k) d.weights[i * m + k] /= sum;
    }
    return d;
}

} // namespace glint
