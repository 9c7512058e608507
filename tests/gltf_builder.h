// glTF 2.0 files made in memory for the tests and the glTF fuzzer's seeds (no downloaded
// models): a JSON document whose one buffer holds every accessor's bytes, written as .gltf (a
// base64 data URI, or an external .bin) or as .glb.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace glint::testing {

class GltfBuilder {
  public:
    using json = nlohmann::json;
    json doc = json::object();

    GltfBuilder() {
        doc["asset"] = {{"version", "2.0"}};
        for (const char* key : {"buffers", "bufferViews", "accessors", "meshes", "nodes",
                                "materials", "textures", "images", "samplers", "cameras"})
            doc[key] = json::array();
        doc["scenes"] = json::array({json{{"nodes", json::array()}}});
        doc["scene"] = 0;
    }

    // A buffer view over `bytes` appended to the buffer (4-byte aligned); its index.
    int view(const void* bytes, std::size_t size) {
        while (bin_.size() % 4) bin_.push_back('\0');
        const std::size_t offset = bin_.size();
        bin_.append(static_cast<const char*>(bytes), size);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
        return static_cast<int>(doc["bufferViews"].size() - 1);
    }

    // An accessor of float tuples (`type`: "SCALAR", "VEC2", "VEC3") or unsigned ints.
    int floats(const std::vector<float>& values, const char* type, int width) {
        const int v = view(values.data(), values.size() * sizeof(float));
        doc["accessors"].push_back({{"bufferView", v},
                                    {"componentType", 5126},
                                    {"count", values.size() / static_cast<std::size_t>(width)},
                                    {"type", type}});
        return static_cast<int>(doc["accessors"].size() - 1);
    }
    int indices(const std::vector<std::uint32_t>& values) {
        const int v = view(values.data(), values.size() * sizeof(std::uint32_t));
        doc["accessors"].push_back(
            {{"bufferView", v}, {"componentType", 5125}, {"count", values.size()}, {"type", "SCALAR"}});
        return static_cast<int>(doc["accessors"].size() - 1);
    }

    // A mesh of one indexed triangle primitive; its index.
    int mesh(const std::vector<float>& xyz, const std::vector<std::uint32_t>& corners,
             int material = -1, const std::vector<float>& uv = {}) {
        json primitive = {{"attributes", {{"POSITION", floats(xyz, "VEC3", 3)}}},
                          {"indices", indices(corners)}};
        if (!uv.empty()) primitive["attributes"]["TEXCOORD_0"] = floats(uv, "VEC2", 2);
        if (material >= 0) primitive["material"] = material;
        doc["meshes"].push_back({{"primitives", json::array({primitive})}});
        return static_cast<int>(doc["meshes"].size() - 1);
    }

    // A node (its JSON fields given) appended; a root of the scene unless it is someone's child.
    int node(json fields, bool root = true) {
        doc["nodes"].push_back(std::move(fields));
        const int index = static_cast<int>(doc["nodes"].size() - 1);
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }

    // An image stored in the buffer (PNG bytes), used by a texture with `sampler`; its index.
    int texture(const std::string& png, json sampler = json::object()) {
        doc["images"].push_back({{"bufferView", view(png.data(), png.size())},
                                 {"mimeType", "image/png"}});
        doc["samplers"].push_back(std::move(sampler));
        doc["textures"].push_back({{"source", doc["images"].size() - 1},
                                   {"sampler", doc["samplers"].size() - 1}});
        return static_cast<int>(doc["textures"].size() - 1);
    }

    const std::string& bin() const { return bin_; }

    // The .gltf text with the buffer as a base64 data URI.
    std::string gltf() const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin_.size()},
                                     {"uri", "data:application/octet-stream;base64," + base64(bin_)}}});
        return d.dump();
    }
    // The .gltf text naming the buffer as an external file.
    std::string gltf_with_file(const std::string& uri) const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin_.size()}, {"uri", uri}}});
        return d.dump();
    }
    // The .glb bytes: header, JSON chunk, BIN chunk.
    std::string glb() const {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin_.size()}}});
        return glb_of(d.dump(), bin_);
    }
    // A GLB of this JSON text and these BIN chunk bytes (each padded to 4 bytes).
    static std::string glb_of(std::string text, std::string bin) {
        while (text.size() % 4) text += ' ';
        while (bin.size() % 4) bin += '\0';
        std::string out = "glTF";
        const auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
        };
        u32(2);
        u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
        u32(static_cast<std::uint32_t>(text.size()));
        u32(0x4E4F534A);
        out += text;
        u32(static_cast<std::uint32_t>(bin.size()));
        u32(0x004E4942);
        out += bin;
        return out;
    }

    static std::string base64(const std::string& bytes) {
        static const char* digits =
            "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        std::size_t i = 0;
        for (; i + 2 < bytes.size(); i += 3) {
            const auto b = [&](std::size_t k) { return static_cast<unsigned char>(bytes[i + k]); };
            const std::uint32_t v = (b(0) << 16) | (b(1) << 8) | b(2);
            for (int s = 18; s >= 0; s -= 6) out += digits[(v >> s) & 63];
        }
        if (i < bytes.size()) {
            std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
            if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
            out += digits[(v >> 18) & 63];
            out += digits[(v >> 12) & 63];
            out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
            out += '=';
        }
        return out;
    }

  private:
    std::string bin_;
};

} // namespace glint::testing
