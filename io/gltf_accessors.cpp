#include "io/gltf_accessors.h"

#include "io/error.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace glint {

void GltfAccessors::fail(const std::string& place, const std::string& what) const {
    throw SceneError(name_ + ": " + place + ": " + what);
}

int GltfAccessors::component_bytes(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

double GltfAccessors::component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<std::int8_t>(*p);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

const unsigned char* GltfAccessors::view_bytes(int view, std::size_t offset, std::size_t count,
                                           std::size_t element, std::size_t stride,
                                           const std::string& at) const {
    if (view < 0 || static_cast<std::size_t>(view) >= m_.bufferViews.size())
        fail(at, "no buffer view " + std::to_string(view));
    const tinygltf::BufferView& v = m_.bufferViews[static_cast<std::size_t>(view)];
    const std::string view_at = pointer("bufferViews", static_cast<std::size_t>(view));
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m_.buffers.size())
        fail(view_at + "/buffer", "no buffer " + std::to_string(v.buffer));
    const std::size_t size = m_.buffers[static_cast<std::size_t>(v.buffer)].data.size();
    if (v.byteLength > size || v.byteOffset > size - v.byteLength)
        fail(view_at, "bytes " + std::to_string(v.byteOffset) + " to " +
                          std::to_string(v.byteOffset + v.byteLength) + " are beyond buffer " +
                          std::to_string(v.buffer) + "'s " + std::to_string(size) + " bytes");
    if (count > 0 && (element > v.byteLength || offset > v.byteLength - element ||
                      (count - 1) > (v.byteLength - element - offset) / stride))
        fail(at, std::to_string(count) + " elements of " + std::to_string(element) +
                     " bytes, " + std::to_string(stride) + " apart from byte " +
                     std::to_string(offset) + ", run past the end of " + view_at + " (" +
                     std::to_string(v.byteLength) + " bytes)");
    return m_.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + offset;
}

std::vector<double> GltfAccessors::read_accessor(int index, int type, int width,
                                             std::initializer_list<int> component_types,
                                             const std::string& use,
                                             std::size_t max_count) const {
    if (index < 0 || static_cast<std::size_t>(index) >= m_.accessors.size())
        fail(use, "no accessor " + std::to_string(index));
    const tinygltf::Accessor& a = m_.accessors[static_cast<std::size_t>(index)];
    const std::string at = pointer("accessors", static_cast<std::size_t>(index));
    if (a.type != type)
        fail(at + "/type", "is not the type " + use + " needs (" +
                               (type == TINYGLTF_TYPE_SCALAR ? "SCALAR"
                                : type == TINYGLTF_TYPE_MAT4 ? "MAT4"
                                                             : "VEC" + std::to_string(width)) +
                               ")");
    if (std::find(component_types.begin(), component_types.end(), a.componentType) ==
        component_types.end())
        fail(at + "/componentType", "component type " + std::to_string(a.componentType) +
                                        " is not one " + use + " may have");
    if (a.count == 0) fail(at + "/count", "must be at least 1");
    if (a.count > max_count)
        fail(at + "/count", std::to_string(a.count) + " elements; the limit is " +
                                std::to_string(max_count));
    const std::size_t bytes = static_cast<std::size_t>(component_bytes(a.componentType));
    const std::size_t element = bytes * static_cast<std::size_t>(width);
    std::vector<double> out(a.count * static_cast<std::size_t>(width), 0.0);
    if (a.bufferView >= 0) {
        if (static_cast<std::size_t>(a.bufferView) >= m_.bufferViews.size())
            fail(at + "/bufferView", "no buffer view " + std::to_string(a.bufferView));
        const tinygltf::BufferView& v = m_.bufferViews[static_cast<std::size_t>(a.bufferView)];
        const std::size_t stride = v.byteStride ? v.byteStride : element;
        if (v.byteStride && (v.byteStride < element || v.byteStride % bytes != 0))
            fail(pointer("bufferViews", static_cast<std::size_t>(a.bufferView)) + "/byteStride",
                 "a stride of " + std::to_string(v.byteStride) + " bytes cannot hold " +
                     at + "'s elements of " + std::to_string(element));
        const unsigned char* p =
            view_bytes(a.bufferView, a.byteOffset, a.count, element, stride, at);
        for (std::size_t i = 0; i < a.count; ++i)
            for (int c = 0; c < width; ++c)
                out[i * width + c] =
                    component(p + i * stride + c * bytes, a.componentType, a.normalized);
    }
    if (a.sparse.isSparse) {
        const std::string sparse_at = at + "/sparse";
        if (a.sparse.count < 1 || static_cast<std::size_t>(a.sparse.count) > a.count)
            fail(sparse_at + "/count", "must be 1 to the accessor's count");
        const auto n = static_cast<std::size_t>(a.sparse.count);
        const int index_type = a.sparse.indices.componentType;
        const int index_bytes = component_bytes(index_type);
        if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(sparse_at + "/indices/componentType", "must be an unsigned integer type");
        if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
            fail(sparse_at, "byte offsets must not be negative");
        const unsigned char* indices =
            view_bytes(a.sparse.indices.bufferView,
                       static_cast<std::size_t>(a.sparse.indices.byteOffset), n,
                       static_cast<std::size_t>(index_bytes),
                       static_cast<std::size_t>(index_bytes), sparse_at + "/indices");
        const unsigned char* values =
            view_bytes(a.sparse.values.bufferView,
                       static_cast<std::size_t>(a.sparse.values.byteOffset), n, element,
                       element, sparse_at + "/values");
        for (std::size_t k = 0; k < n; ++k) {
            const auto target =
                static_cast<std::size_t>(component(indices + k * index_bytes, index_type, false));
            if (target >= a.count)
                fail(sparse_at + "/indices", "index " + std::to_string(k) + " is " +
                                                 std::to_string(target) + ", beyond count " +
                                                 std::to_string(a.count));
            for (int c = 0; c < width; ++c)
                out[target * width + c] =
                    component(values + k * element + c * bytes, a.componentType, a.normalized);
        }
    }
    return out;
}

} // namespace glint
