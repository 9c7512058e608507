#include "io/gltf_decoders.h"

#include "io/error.h"
#include "io/gltf_accessors.h"
#include "io/gltf_container.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>

namespace glint {

namespace {

// The components a glTF accessor type has (VEC3: 3), or 0 for none known.
int components(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
    }
}

// The most bytes one decoded view may hold: a few bytes of compressed data may claim any size.
constexpr std::size_t kMaxDecodedBytes = std::size_t{1} << 28;

// A buffer the decoders append: its bytes, and views over them made as they are filled.
class DecodedBuffer {
  public:
    explicit DecodedBuffer(tinygltf::Model& model) : model_(model) {}

    // `size` bytes (4-byte aligned) at the buffer's end: where they start.
    std::size_t region(std::size_t size) {
        while (bytes_.size() % 4) bytes_.push_back(0);
        const std::size_t offset = bytes_.size();
        bytes_.resize(offset + size);
        return offset;
    }
    // The index the buffer will have in the model (commit() puts it there).
    int index() const { return static_cast<int>(model_.buffers.size()); }
    // A new buffer view of `size` bytes at the buffer's end; its index, and where its bytes start.
    std::pair<int, std::size_t> view(std::size_t size) {
        const std::size_t offset = region(size);
        tinygltf::BufferView v;
        v.buffer = index();
        v.byteOffset = offset;
        v.byteLength = size;
        model_.bufferViews.push_back(v);
        return {static_cast<int>(model_.bufferViews.size() - 1), offset};
    }
    unsigned char* at(std::size_t offset) { return bytes_.data() + offset; }

    // Appends the buffer to the model, if any view was made.
    void commit() {
        if (bytes_.empty()) return;
        tinygltf::Buffer b;
        b.data = std::move(bytes_);
        model_.buffers.push_back(std::move(b));
    }

  private:
    tinygltf::Model& model_;
    std::vector<unsigned char> bytes_;
};

class DracoDecoder {
  public:
    DracoDecoder(tinygltf::Model& model, const std::string& name)
        : m_(model), name_(name), out_(model) {}

    void run() {
        for (std::size_t mesh = 0; mesh < m_.meshes.size(); ++mesh)
            for (std::size_t p = 0; p < m_.meshes[mesh].primitives.size(); ++p) {
                tinygltf::Primitive& primitive = m_.meshes[mesh].primitives[p];
                const auto it = primitive.extensions.find("KHR_draco_mesh_compression");
                if (it == primitive.extensions.end()) continue;
                const std::string at = pointer("meshes", mesh) + "/primitives/" +
                                       std::to_string(p) + "/extensions/KHR_draco_mesh_compression";
                const tinygltf::Value extension = it->second;
                primitive.extensions.erase(it);
                decode(primitive, extension, at);
            }
        out_.commit();
    }

  private:
    [[noreturn]] void fail(const std::string& place, const std::string& what) const {
        throw SceneError(name_ + ": " + place + ": " + what);
    }

    void decode(tinygltf::Primitive& p, const tinygltf::Value& extension, const std::string& at) {
        const tinygltf::Value& view_index = extension.Get("bufferView");
        if (!view_index.IsInt() || view_index.GetNumberAsInt() < 0 ||
            static_cast<std::size_t>(view_index.GetNumberAsInt()) >= m_.bufferViews.size())
            fail(at + "/bufferView", "no such buffer view");
        const tinygltf::BufferView& view = m_.bufferViews[static_cast<std::size_t>(view_index.GetNumberAsInt())];
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= m_.buffers.size())
            fail(at + "/bufferView", "its buffer view names no buffer");
        const std::vector<unsigned char>& data = m_.buffers[static_cast<std::size_t>(view.buffer)].data;
        if (view.byteLength > data.size() || view.byteOffset > data.size() - view.byteLength)
            fail(at + "/bufferView", "its bytes run past the end of buffer " + std::to_string(view.buffer));
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
        if (!decoded.ok())
            fail(at, std::string("the Draco data does not decode: ") + decoded.status().error_msg());
        const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
        if (!mesh || mesh->num_faces() == 0) fail(at, "the Draco data holds no triangle");
        indices(p, *mesh, at);
        const tinygltf::Value& attributes = extension.Get("attributes");
        if (!attributes.IsObject()) fail(at + "/attributes", "must be an object");
        for (const auto& [key, id] : attributes.Get<tinygltf::Value::Object>()) {
            const std::string attribute_at = at + "/attributes/" + printable(key);
            const auto it = p.attributes.find(key);
            if (it == p.attributes.end())
                fail(attribute_at, "names an attribute the primitive does not have");
            if (!id.IsInt() || id.GetNumberAsInt() < 0)
                fail(attribute_at, "must be a Draco attribute id");
            const draco::PointAttribute* a =
                mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.GetNumberAsInt()));
            if (!a) fail(attribute_at, "the Draco data has no attribute " + std::to_string(id.GetNumberAsInt()));
            it->second = attribute(it->second, *mesh, *a, attribute_at);
        }
    }

    // The accessor `index` declares (count, type, component type) filled from the decoded mesh:
    // a copy of it over the new bytes, its index.
    int attribute(int index, const draco::Mesh& mesh, const draco::PointAttribute& a,
                  const std::string& at) {
        if (index < 0 || static_cast<std::size_t>(index) >= m_.accessors.size())
            fail(at, "the primitive's accessor " + std::to_string(index) + " does not exist");
        tinygltf::Accessor accessor = m_.accessors[static_cast<std::size_t>(index)];
        const int n = components(accessor.type);
        const int bytes = GltfAccessors::component_bytes(accessor.componentType);
        if (n == 0 || bytes == 0)
            fail(pointer("accessors", static_cast<std::size_t>(index)), "a type Draco data cannot fill");
        if (accessor.count != mesh.num_points())
            fail(pointer("accessors", static_cast<std::size_t>(index)) + "/count",
                 std::to_string(accessor.count) + " elements, where the Draco data decodes " +
                     std::to_string(mesh.num_points()) + " vertices");
        if (a.num_components() != n)
            fail(at, "the Draco attribute has " + std::to_string(a.num_components()) +
                         " components, the accessor " + std::to_string(n));
        const std::size_t element = static_cast<std::size_t>(n * bytes);
        if (accessor.count > kMaxDecodedBytes / element)
            fail(at, std::to_string(accessor.count) + " decoded vertices; the limit is " +
                         std::to_string(kMaxDecodedBytes / element));
        const auto [view, offset] = out_.view(element * accessor.count);
        for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
            unsigned char* to = out_.at(offset + element * i.value());
            const draco::AttributeValueIndex v = a.mapped_index(i);
            bool ok = false;
            switch (accessor.componentType) {
            case TINYGLTF_COMPONENT_TYPE_BYTE: ok = convert<std::int8_t>(a, v, n, to); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: ok = convert<std::uint8_t>(a, v, n, to); break;
            case TINYGLTF_COMPONENT_TYPE_SHORT: ok = convert<std::int16_t>(a, v, n, to); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: ok = convert<std::uint16_t>(a, v, n, to); break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: ok = convert<std::uint32_t>(a, v, n, to); break;
            default: ok = convert<float>(a, v, n, to); break;
            }
            if (!ok) fail(at, "vertex " + std::to_string(i.value()) + " does not convert");
        }
        accessor.bufferView = view;
        accessor.byteOffset = 0;
        accessor.sparse.isSparse = false;
        m_.accessors.push_back(accessor);
        return static_cast<int>(m_.accessors.size() - 1);
    }

    template <class T>
    static bool convert(const draco::PointAttribute& a, draco::AttributeValueIndex v, int n,
                        unsigned char* to) {
        T values[4] = {};
        if (!a.ConvertValue<T>(v, static_cast<std::int8_t>(n), values)) return false;
        std::memcpy(to, values, sizeof(T) * static_cast<std::size_t>(n));
        return true;
    }

    // The primitive's indices from the decoded faces, in its indices accessor's component type
    // (a new 32-bit one where it has none).
    void indices(tinygltf::Primitive& p, const draco::Mesh& mesh, const std::string& at) {
        tinygltf::Accessor accessor;
        if (p.indices >= 0) {
            if (static_cast<std::size_t>(p.indices) >= m_.accessors.size())
                fail(at, "the primitive's indices accessor does not exist");
            accessor = m_.accessors[static_cast<std::size_t>(p.indices)];
        } else {
            accessor.type = TINYGLTF_TYPE_SCALAR;
            accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        }
        const std::size_t count = 3 * static_cast<std::size_t>(mesh.num_faces());
        const std::string accessor_at =
            p.indices >= 0 ? pointer("accessors", static_cast<std::size_t>(p.indices)) : at;
        if (p.indices >= 0 && accessor.count != count)
            fail(accessor_at + "/count", std::to_string(accessor.count) +
                                             " indices, where the Draco data decodes " +
                                             std::to_string(count));
        accessor.count = count;
        const int bytes = GltfAccessors::component_bytes(accessor.componentType);
        if (accessor.type != TINYGLTF_TYPE_SCALAR || bytes == 0 ||
            accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail(accessor_at, "indices are unsigned integer scalars");
        const std::uint64_t largest = bytes == 1 ? 0xff : bytes == 2 ? 0xffff : 0xffffffff;
        if (count > kMaxDecodedBytes / static_cast<std::size_t>(bytes))
            fail(at, std::to_string(count) + " decoded indices; the limit is " +
                         std::to_string(kMaxDecodedBytes / static_cast<std::size_t>(bytes)));
        const auto [view, offset] = out_.view(count * static_cast<std::size_t>(bytes));
        for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t index = mesh.face(f)[c].value();
                if (index >= mesh.num_points() || index > largest)
                    fail(at, "face " + std::to_string(f.value()) + " names vertex " +
                                 std::to_string(index) + ", beyond the decoded vertices");
                unsigned char* to = out_.at(offset + (3 * f.value() + c) * static_cast<std::size_t>(bytes));
                if (bytes == 1) *to = static_cast<std::uint8_t>(index);
                else if (bytes == 2) {
                    const auto v = static_cast<std::uint16_t>(index);
                    std::memcpy(to, &v, 2);
                } else {
                    std::memcpy(to, &index, 4);
                }
            }
        accessor.bufferView = view;
        accessor.byteOffset = 0;
        accessor.sparse.isSparse = false;
        m_.accessors.push_back(accessor);
        p.indices = static_cast<int>(m_.accessors.size() - 1);
    }

    tinygltf::Model& m_;
    const std::string& name_;
    DecodedBuffer out_;
};

// EXT_meshopt_compression: each compressed buffer view decoded in place of its fallback bytes.
class MeshoptDecoder {
  public:
    MeshoptDecoder(tinygltf::Model& model, const std::string& name)
        : m_(model), name_(name), out_(model) {}

    void run() {
        for (std::size_t v = 0; v < m_.bufferViews.size(); ++v) {
            tinygltf::BufferView& view = m_.bufferViews[v];
            const auto it = view.extensions.find("EXT_meshopt_compression");
            if (it == view.extensions.end()) continue;
            const tinygltf::Value extension = it->second;
            view.extensions.erase(it);
            decode(view, extension, pointer("bufferViews", v) + "/extensions/EXT_meshopt_compression");
        }
        out_.commit();
    }

  private:
    [[noreturn]] void fail(const std::string& place, const std::string& what) const {
        throw SceneError(name_ + ": " + place + ": " + what);
    }

    std::size_t number(const tinygltf::Value& o, const char* key, const std::string& at,
                       std::optional<std::size_t> otherwise = std::nullopt) const {
        const tinygltf::Value& v = o.Get(key);
        if (!v.IsNumber()) {
            if (otherwise) return *otherwise;
            fail(at + "/" + key, "must be given, a whole number");
        }
        const double d = v.GetNumberAsDouble();
        if (!(d >= 0 && d <= 1e15) || d != std::floor(d))
            fail(at + "/" + key, "must be a whole number, not negative");
        return static_cast<std::size_t>(d);
    }
    std::string text(const tinygltf::Value& o, const char* key, const std::string& at,
                     const std::string& otherwise) const {
        const tinygltf::Value& v = o.Get(key);
        if (v.IsString()) return v.Get<std::string>();
        if (o.Has(key)) fail(at + "/" + key, "must be a string");
        return otherwise;
    }

    void decode(tinygltf::BufferView& view, const tinygltf::Value& e, const std::string& at) {
        const std::size_t buffer = number(e, "buffer", at);
        const std::size_t offset = number(e, "byteOffset", at, 0);
        const std::size_t length = number(e, "byteLength", at);
        const std::size_t stride = number(e, "byteStride", at);
        const std::size_t count = number(e, "count", at);
        const std::string mode = text(e, "mode", at, "");
        const std::string filter = text(e, "filter", at, "NONE");
        if (buffer >= m_.buffers.size()) fail(at + "/buffer", "no buffer " + std::to_string(buffer));
        const std::vector<unsigned char>& data = m_.buffers[buffer].data;
        if (length > data.size() || offset > data.size() - length)
            fail(at, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                         " are beyond buffer " + std::to_string(buffer) + "'s " +
                         std::to_string(data.size()) + " bytes");
        if (view.byteLength > kMaxDecodedBytes)
            fail(at, "the view's " + std::to_string(view.byteLength) + " bytes are beyond the " +
                         std::to_string(kMaxDecodedBytes) + " glint decodes");
        if (count == 0) fail(at + "/count", "must be at least 1");
        if (stride == 0 || count > view.byteLength / stride || count * stride != view.byteLength)
            fail(at, std::to_string(count) + " elements of " + std::to_string(stride) +
                         " bytes do not fill the view's " + std::to_string(view.byteLength));
        // The decoders assert rather than check these (meshoptimizer.h).
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0 || stride > 256)
                fail(at + "/byteStride", "an ATTRIBUTES stride is a multiple of 4, at most 256");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) fail(at + "/byteStride", "an index is 2 or 4 bytes");
            if (mode == "TRIANGLES" && count % 3 != 0)
                fail(at + "/count", "TRIANGLES holds whole triangles");
            if (filter != "NONE") fail(at + "/filter", "only ATTRIBUTES are filtered");
        } else {
            fail(at + "/mode", "must be ATTRIBUTES, TRIANGLES or INDICES, not '" + printable(mode) + "'");
        }
        const std::size_t to = out_.region(view.byteLength);
        unsigned char* bytes = out_.at(to);
        const unsigned char* from = data.data() + offset;
        const int status = mode == "ATTRIBUTES" ? meshopt_decodeVertexBuffer(bytes, count, stride, from, length)
                           : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(bytes, count, stride, from, length)
                                                 : meshopt_decodeIndexSequence(bytes, count, stride, from, length);
        if (status != 0)
            fail(at, "the meshopt data does not decode (meshoptimizer's error " + std::to_string(status) + ")");
        if (filter == "OCTAHEDRAL") {
            if (stride != 4 && stride != 8) fail(at + "/byteStride", "OCTAHEDRAL needs 4 or 8 bytes");
            meshopt_decodeFilterOct(bytes, count, stride);
        } else if (filter == "QUATERNION") {
            if (stride != 8) fail(at + "/byteStride", "QUATERNION needs 8 bytes");
            meshopt_decodeFilterQuat(bytes, count, stride);
        } else if (filter == "EXPONENTIAL") {
            meshopt_decodeFilterExp(bytes, count, stride);
        } else if (filter != "NONE") {
            fail(at + "/filter", "must be NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL, not '" +
                                     printable(filter) + "'");
        }
        view.buffer = out_.index();
        view.byteOffset = to;
    }

    tinygltf::Model& m_;
    const std::string& name_;
    DecodedBuffer out_;
};

} // namespace

void decode_draco(tinygltf::Model& model, const std::string& name) {
    DracoDecoder(model, name).run();
}

void decode_meshopt(tinygltf::Model& model, const std::string& name) {
    MeshoptDecoder(model, name).run();
}

} // namespace glint
