#include "io/gltf_instances.h"

#include "io/gltf_accessors.h"
#include "io/gltf_animation.h"

#include <cmath>
#include <optional>

namespace glint {

std::vector<DMat4> read_instances(const tinygltf::Node& node, const std::string& at,
                                  const GltfAccessors& accessors, std::size_t max_count) {
    const auto it = node.extensions.find("EXT_mesh_gpu_instancing");
    if (it == node.extensions.end()) return {};
    const std::string ext_at = at + "/extensions/EXT_mesh_gpu_instancing";
    const tinygltf::Value& attributes = it->second.Get("attributes");
    if (!attributes.IsObject())
        accessors.fail(ext_at + "/attributes", "must name TRANSLATION, ROTATION or SCALE");
    std::optional<std::size_t> count;
    std::string first;
    // One attribute's values, `width` a instance; its count the same as the others'.
    const auto read = [&](const char* key, int type, int width) -> std::vector<double> {
        if (!attributes.Has(key)) return {};
        const std::string use = ext_at + "/attributes/" + key;
        const tinygltf::Value& index = attributes.Get(key);
        if (!index.IsInt()) accessors.fail(use, "must be an accessor index");
        std::vector<double> v = accessors.read_accessor(
            index.GetNumberAsInt(), type, width,
            {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
             TINYGLTF_COMPONENT_TYPE_SHORT},
            use, max_count);
        const std::size_t n = v.size() / static_cast<std::size_t>(width);
        if (count && n != *count)
            accessors.fail(use, std::to_string(n) + " instances, where " + first + " has " +
                                    std::to_string(*count) + " (every attribute has one per instance)");
        if (!count) count = n, first = key;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (!(std::abs(v[i]) <= kMaxCoordinate))
                accessors.fail(use, "instance " + std::to_string(i / static_cast<std::size_t>(width)) +
                                        ": values must be finite and within ±1e15");
        return v;
    };
    const std::vector<double> t = read("TRANSLATION", TINYGLTF_TYPE_VEC3, 3);
    const std::vector<double> r = read("ROTATION", TINYGLTF_TYPE_VEC4, 4);
    const std::vector<double> s = read("SCALE", TINYGLTF_TYPE_VEC3, 3);
    for (const auto& [key, value] : attributes.Get<tinygltf::Value::Object>())
        if (key != "TRANSLATION" && key != "ROTATION" && key != "SCALE")
            accessors.fail(ext_at + "/attributes/" + key,
                           "an instance attribute glint does not know (TRANSLATION, ROTATION or "
                           "SCALE)");
    if (!count) accessors.fail(ext_at + "/attributes", "must name TRANSLATION, ROTATION or SCALE");
    std::vector<DMat4> out;
    out.reserve(*count);
    for (std::size_t i = 0; i < *count; ++i) {
        NodeTrs trs;
        if (!t.empty()) trs.translation = {t[3 * i], t[3 * i + 1], t[3 * i + 2]};
        if (!r.empty()) {
            const glm::dvec4 q(r[4 * i], r[4 * i + 1], r[4 * i + 2], r[4 * i + 3]);
            if (!(glm::length(q) > 0))
                accessors.fail(ext_at + "/attributes/ROTATION",
                               "instance " + std::to_string(i) + ": a rotation must not be zero");
            trs.rotation = q / glm::length(q);
        }
        if (!s.empty()) trs.scale = {s[3 * i], s[3 * i + 1], s[3 * i + 2]};
        out.push_back(trs_matrix(trs));
    }
    return out;
}

} // namespace glint
