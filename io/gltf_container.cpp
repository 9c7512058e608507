#include "io/gltf_container.h"

#include "io/error.h"
#include "io/read_text.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>

namespace glint {

std::string pointer(const std::string& array, std::size_t index) {
    return "/" + array + "/" + std::to_string(index);
}

std::string decode_uri(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uri[i + 1]) &&
            std::isxdigit(uri[i + 2])) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

bool is_data_uri(const std::string& uri) {
    return uri.rfind("data:", 0) == 0;
}

const std::set<std::string> kKnownExtensions = {
    "KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_emissive_strength", "KHR_texture_transform", "KHR_materials_unlit",
    "EXT_mesh_gpu_instancing", "KHR_mesh_quantization", "KHR_draco_mesh_compression",
    "EXT_texture_webp", "EXT_meshopt_compression"};

namespace {

using json = nlohmann::json;

// A glTF nests no deeper than its extras do; this bounds the parser's stack.
constexpr int kMaxGltfJsonDepth = 64;

constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

std::uint32_t le32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
}

// The bytes a base64 data URI holds, or nothing if it is not one glint can count.
std::optional<std::size_t> data_uri_bytes(const std::string& uri) {
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
        return std::nullopt;
    std::size_t n = uri.size() - comma - 1;
    std::size_t padding = 0;
    while (padding < 2 && n > 0 && uri[comma + n - padding] == '=') ++padding;
    return n / 4 * 3 - (n % 4 == 0 ? padding : 0) + (n % 4 == 0 ? 0 : (n % 4) * 3 / 4);
}

// Everything tinygltf would read unchecked or that glint names places for: the GLB container,
// the JSON's nesting, required extensions, the buffers' sizes against their files, and the
// byte ranges of images stored in buffer views (tinygltf hands those to the image callback
// without a bound). Returns the external buffers' bytes, read once, by decoded URI.
class Precheck {
  public:
    Precheck(const std::string& bytes, const std::string& name, const ModelFiles& files)
        : bytes_(bytes), name_(name), files_(files) {}

    std::map<std::string, std::vector<unsigned char>> run(bool& glb, std::vector<std::string>& warnings) {
        glb = bytes_.size() >= 4 && le32(bytes_, 0) == kGlbMagic;
        std::string text = glb ? glb_json() : bytes_;
        if (glb) glb_json_length_ = le32(bytes_, 12);
        check_json_nesting(text, name_, kMaxGltfJsonDepth);
        try {
            root_ = json::parse(text);
        } catch (const json::exception& e) {
            fail("", std::string("malformed JSON: ") + e.what());
        }
        if (!root_.is_object()) fail("/", "a glTF file is a JSON object");
        version();
        extensions(warnings);
        compressed();
        std::map<std::string, std::vector<unsigned char>> files;
        const json& buffers = array("buffers");
        for (std::size_t b = 0; b < buffers.size(); ++b) buffer(b, buffers[b], files);
        const json& images = array("images");
        for (std::size_t i = 0; i < images.size(); ++i)
            if (images[i].is_object() && images[i].contains("bufferView"))
                image_view(i, images[i]["bufferView"]);
        return files;
    }

    // The bytes tinygltf parses: the file's, or where compressed() left parts out, the JSON
    // without them (in a GLB, beside the file's BIN chunk).
    std::string parsed_bytes() const {
        if (!rewritten_) return bytes_;
        std::string text = root_.dump();
        if (!glb_json_length_) return text;
        while (text.size() % 4) text += ' ';
        const std::string bin = bytes_.substr(20 + *glb_json_length_);
        std::string out = "glTF";
        const auto u32 = [&](std::uint64_t v) {
            for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
        };
        u32(2);
        u32(20 + text.size() + bin.size());
        u32(text.size());
        u32(kJsonChunk);
        return out + text + bin;
    }

    // What compressed() left out, put back into the parsed model: where tinygltf kept the
    // primitive (it drops a malformed one: decode_draco then gives it indices of its own).
    void restore(tinygltf::Model& model) const {
        for (const auto& [mesh, primitive, indices] : draco_indices_)
            if (mesh < model.meshes.size() && primitive < model.meshes[mesh].primitives.size())
                model.meshes[mesh].primitives[primitive].indices =
                    static_cast<int>(std::min<std::size_t>(indices, INT32_MAX));
    }

  private:
    [[noreturn]] void fail(const std::string& place, const std::string& what) const {
        throw SceneError(name_ + ": " + (place.empty() ? "" : place + ": ") + what);
    }

    // Compressed files hold parts without bytes that tinygltf refuses: a Draco primitive's
    // indices accessor (no buffer view until decode_draco fills it) and EXT_meshopt_compression's
    // fallback buffers (no uri: decode_meshopt fills the views over them). The JSON tinygltf
    // parses leaves the indices out (restore() puts them back) and gives each fallback buffer one
    // byte of its own.
    void compressed() {
        const json& meshes = array("meshes");
        for (std::size_t m = 0; m < meshes.size(); ++m) {
            if (!meshes[m].is_object() || !meshes[m].contains("primitives") ||
                !meshes[m]["primitives"].is_array())
                continue;
            const json& primitives = meshes[m]["primitives"];
            for (std::size_t p = 0; p < primitives.size(); ++p) {
                const json& primitive = primitives[p];
                if (!primitive.is_object() || !primitive.contains("indices") ||
                    !primitive["indices"].is_number_unsigned() ||
                    !primitive.contains("extensions") || !primitive["extensions"].is_object() ||
                    !primitive["extensions"].contains("KHR_draco_mesh_compression"))
                    continue;
                draco_indices_.push_back({m, p, primitive["indices"].get<std::size_t>()});
                root_["meshes"][m]["primitives"][p].erase("indices");
                rewritten_ = true;
            }
        }
        const json& buffers = array("buffers");
        for (std::size_t b = 0; b < buffers.size(); ++b) {
            const json& buffer = buffers[b];
            if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("extensions") ||
                !buffer["extensions"].is_object())
                continue;
            const auto meshopt = buffer["extensions"].find("EXT_meshopt_compression");
            if (meshopt == buffer["extensions"].end() || !meshopt->is_object() ||
                meshopt->value("fallback", false) != true)
                continue;
            root_["buffers"][b]["uri"] = "data:application/octet-stream;base64,AA==";
            root_["buffers"][b]["byteLength"] = std::uint64_t{1};
            rewritten_ = true;
        }
    }

    const json& array(const char* key) const {
        static const json empty = json::array();
        if (!root_.contains(key)) return empty;
        if (!root_[key].is_array()) fail(std::string("/") + key, "must be an array");
        return root_[key];
    }

    // A glTF 1.0 file says so in its asset (its buffers are an object, which would otherwise be
    // the first complaint).
    void version() const {
        // find(), not []: on a const json, [] of a missing key is undefined behaviour.
        const auto asset = root_.find("asset");
        if (asset == root_.end() || !asset->is_object()) return;
        const auto version = asset->find("version");
        if (version == asset->end()) return;
        const json& v = *version;
        if (v.is_string() && v.get<std::string>().starts_with("1."))
            fail("/asset/version", "glTF " + printable(v.get<std::string>()) +
                                       ": glint reads glTF 2.0 (convert the file, e.g. with "
                                       "gltf-pipeline or Blender)");
    }

    // GLB (glTF 2.0 §4.4): a 12-byte header, a JSON chunk, an optional BIN chunk.
    std::string glb_json() const {
        if (bytes_.size() < 20) fail("GLB header", "the file is shorter than a GLB header");
        if (le32(bytes_, 4) != 2)
            fail("GLB header", "version " + std::to_string(le32(bytes_, 4)) + ", glint reads 2");
        const std::uint64_t length = le32(bytes_, 8);
        if (length != bytes_.size())
            fail("GLB header", "says " + std::to_string(length) + " bytes, the file has " +
                                   std::to_string(bytes_.size()));
        const std::uint64_t json_length = le32(bytes_, 12);
        if (le32(bytes_, 16) != kJsonChunk) fail("GLB chunk 0", "is not the JSON chunk");
        if (json_length == 0 || 20 + json_length > length)
            fail("GLB chunk 0", "its length " + std::to_string(json_length) +
                                    " runs past the end of the file");
        const std::uint64_t rest = length - 20 - json_length;
        if (rest > 0) {
            if (rest < 8) fail("GLB chunk 1", "a chunk header is cut short");
            const std::uint64_t bin_length = le32(bytes_, 20 + json_length);
            if (le32(bytes_, 24 + json_length) != kBinChunk)
                fail("GLB chunk 1", "is not the BIN chunk");
            if (8 + bin_length > rest)
                fail("GLB chunk 1", "its length " + std::to_string(bin_length) +
                                        " runs past the end of the file");
            bin_length_ = bin_length;
        }
        return bytes_.substr(20, json_length);
    }

    void extensions(std::vector<std::string>& warnings) const {
        for (const char* key : {"extensionsRequired", "extensionsUsed"}) {
            const json& list = array(key);
            for (std::size_t i = 0; i < list.size(); ++i) {
                if (!list[i].is_string()) fail(pointer(key, i), "must be a string");
                const std::string name = list[i];
                if (kKnownExtensions.contains(name)) continue;
                if (key == std::string("extensionsRequired"))
                    fail(pointer(key, i), "requires extension '" + printable(name) +
                                              "', which glint does not support");
                warnings.push_back(name_ + ": " + pointer(key, i) + ": extension '" +
                                   printable(name) + "' not used: the model renders without it");
            }
        }
    }

    static std::optional<std::uint64_t> count(const json& o, const char* key) {
        if (!o.contains(key)) return std::nullopt;
        if (!o[key].is_number_unsigned()) return std::nullopt;
        return o[key].get<std::uint64_t>();
    }

    void buffer(std::size_t b, const json& o,
                std::map<std::string, std::vector<unsigned char>>& files) const {
        const std::string at = pointer("buffers", b);
        if (!o.is_object()) fail(at, "must be an object");
        const std::optional<std::uint64_t> length = count(o, "byteLength");
        if (!length) fail(at + "/byteLength", "must be given, a whole number of bytes");
        byte_lengths_.push_back(*length);
        if (!o.contains("uri")) {
            if (b != 0 || !bin_length_)
                fail(at, "has no uri, and is not the first buffer of a GLB with a BIN chunk");
            if (*length > *bin_length_)
                fail(at + "/byteLength", "is " + std::to_string(*length) +
                                             ", beyond the BIN chunk's " +
                                             std::to_string(*bin_length_) + " bytes");
            return;
        }
        if (!o["uri"].is_string()) fail(at + "/uri", "must be a string");
        const std::string uri = o["uri"];
        if (is_data_uri(uri)) {
            const std::optional<std::size_t> held = data_uri_bytes(uri);
            if (!held) fail(at + "/uri", "a data URI must be base64 (data:…;base64,…)");
            if (*held < *length)
                fail(at, "its data URI holds " + std::to_string(*held) + " bytes, byteLength says " +
                             std::to_string(*length));
            return;
        }
        const std::string file = decode_uri(uri);
        if (files.contains(file)) return;
        std::string why;
        const std::optional<std::string> data = files_(file, why);
        if (!data) fail(at + "/uri", "cannot read '" + printable(file) + "': " + why);
        if (data->size() < *length)
            fail(at, "'" + printable(file) + "' holds " + std::to_string(data->size()) +
                         " bytes, byteLength says " + std::to_string(*length));
        files.emplace(file, std::vector<unsigned char>(data->begin(), data->end()));
    }

    void image_view(std::size_t i, const json& index) const {
        const std::string at = pointer("images", i) + "/bufferView";
        const json& views = array("bufferViews");
        if (!index.is_number_unsigned() || index.get<std::uint64_t>() >= views.size())
            fail(at, "no such buffer view");
        const std::size_t v = index.get<std::size_t>();
        const json& view = views[v];
        const std::string view_at = pointer("bufferViews", v);
        if (!view.is_object()) fail(view_at, "must be an object");
        const std::optional<std::uint64_t> buffer = count(view, "buffer");
        if (!buffer || *buffer >= byte_lengths_.size()) fail(view_at + "/buffer", "no such buffer");
        const std::uint64_t offset = count(view, "byteOffset").value_or(0);
        const std::optional<std::uint64_t> length = count(view, "byteLength");
        if (!length) fail(view_at + "/byteLength", "must be given, a whole number of bytes");
        const std::uint64_t size = byte_lengths_[*buffer];
        if (*length > size || offset > size - *length)
            fail(view_at, "bytes " + std::to_string(offset) + " to " +
                              std::to_string(offset + *length) + " are beyond buffer " +
                              std::to_string(*buffer) + "'s " + std::to_string(size) + " bytes");
    }

    const std::string& bytes_;
    const std::string& name_;
    const ModelFiles& files_;
    json root_;
    bool rewritten_ = false;
    std::vector<std::array<std::size_t, 3>> draco_indices_; // mesh, primitive, indices accessor
    std::optional<std::uint64_t> glb_json_length_;
    mutable std::optional<std::uint64_t> bin_length_;
    mutable std::vector<std::uint64_t> byte_lengths_;
};

// tinygltf's hooks: images kept as their encoded bytes (decoded by glint when a material uses
// them), external buffers served from what Precheck read.
bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}
bool any_file_exists(const std::string&, void*) {
    return true; // asked before reading: ReadWholeFile answers
}
std::string same_path(const std::string& path, void*) {
    return path;
}
bool read_prechecked(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user) {
    const auto& files = *static_cast<std::map<std::string, std::vector<unsigned char>>*>(user);
    const auto it = files.find(path);
    if (it == files.end()) {
        if (err) *err += "cannot read '" + path + "'\n";
        return false;
    }
    *out = it->second;
    return true;
}
bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "glint does not write glTF files\n";
    return false;
}

} // namespace

tinygltf::Model read_gltf_container(const std::string& bytes, const std::string& name,
                                    const ModelFiles& files, std::vector<std::string>& warnings) {
    bool glb = false;
    Precheck precheck(bytes, name, files);
    std::map<std::string, std::vector<unsigned char>> external = precheck.run(glb, warnings);
    const std::string parsed = precheck.parsed_bytes();
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_image_bytes, nullptr);
    loader.SetFsCallbacks({any_file_exists, same_path, read_prechecked, write_nothing, &external});
    std::string err, warn;
    bool ok = false;
    try {
        const auto* data = reinterpret_cast<const unsigned char*>(parsed.data());
        ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, data,
                                               static_cast<unsigned>(parsed.size()), "")
                 : loader.LoadASCIIFromString(&model, &err, &warn, parsed.data(),
                                              static_cast<unsigned>(parsed.size()), "");
    } catch (const std::exception& e) {
        err = e.what();
        ok = false;
    }
    if (!ok) {
        std::string first = err.substr(0, err.find('\n'));
        throw SceneError(name + ": not a glTF 2.0 file glint can read: " +
                         printable(first.empty() ? "tinygltf gave no reason" : first, 200));
    }
    precheck.restore(model);
    return model;
}

} // namespace glint
