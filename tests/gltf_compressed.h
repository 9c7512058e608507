// Compressed glTF models made with the decoders' own encoders, for the tests
// (tests/gltf_compression_gl_test.cpp) and the glTF fuzzer's seeds (tests/gltf_seeds.cpp): the
// dome (tests/gltf_models.h) as KHR_draco_mesh_compression and as EXT_meshopt_compression, and a
// quad textured through EXT_texture_webp.
#pragma once

#include "gltf_models.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include <memory>
#include <stdexcept>
#include <tuple>

namespace glint::testing {

// The dome's triangles as Draco encodes them (Edgebreaker; positions kept as floats, normals
// quantized to 10 bits, texture coordinates to 12), and how the decoder numbers them.
struct DracoDome {
    std::string bytes;
    std::size_t points = 0;
    int position = -1, normal = -1, uv = -1; // attribute unique ids
};

inline DracoDome encode_dome() {
    const Dome d = dome();
    draco::TriangleSoupMeshBuilder builder;
    const auto faces = static_cast<int>(d.corners.size() / 3);
    builder.Start(faces);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int uv = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < faces; ++f) {
        const auto corner = [&](const std::vector<float>& values, int width, int k) {
            return &values[static_cast<std::size_t>(width) * d.corners[static_cast<std::size_t>(3 * f + k)]];
        };
        for (const auto& [id, values, width] :
             {std::tuple{position, &d.xyz, 3}, std::tuple{normal, &d.normal, 3}, std::tuple{uv, &d.uv, 2}})
            builder.SetAttributeValuesForFace(id, draco::FaceIndex(f), corner(*values, width, 0),
                                              corner(*values, width, 1), corner(*values, width, 2));
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer buffer;
    if (!encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) throw std::runtime_error("Draco encoded nothing");
    DracoDome out;
    out.bytes.assign(buffer.data(), buffer.size());
    // What the decoder makes of it: the accessors must declare its vertex count.
    draco::DecoderBuffer in;
    in.Init(out.bytes.data(), out.bytes.size());
    draco::Decoder decoder;
    const std::unique_ptr<draco::Mesh> decoded = decoder.DecodeMeshFromBuffer(&in).value();
    out.points = decoded->num_points();
    out.position = static_cast<int>(decoded->GetNamedAttribute(draco::GeometryAttribute::POSITION)->unique_id());
    out.normal = static_cast<int>(decoded->GetNamedAttribute(draco::GeometryAttribute::NORMAL)->unique_id());
    out.uv = static_cast<int>(decoded->GetNamedAttribute(draco::GeometryAttribute::TEX_COORD)->unique_id());
    return out;
}

// The dome as a KHR_draco_mesh_compression primitive: its accessors hold no bytes, only what the
// decoded data must be (count, type, component type).
inline std::string draco_dome(const DracoDome& encoded, bool glb = false) {
    return dome_file([&](GltfBuilder& b, const Dome& d) {
        const int view = b.view(encoded.bytes.data(), encoded.bytes.size());
        const auto accessor = [&](std::size_t count, int component, const char* type) {
            b.doc["accessors"].push_back(
                {{"componentType", component}, {"count", count}, {"type", type}});
            return static_cast<int>(b.doc["accessors"].size() - 1);
        };
        b.doc["extensionsUsed"].push_back("KHR_draco_mesh_compression");
        b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        return json{{"attributes", {{"POSITION", accessor(encoded.points, 5126, "VEC3")},
                                    {"NORMAL", accessor(encoded.points, 5126, "VEC3")},
                                    {"TEXCOORD_0", accessor(encoded.points, 5126, "VEC2")}}},
                    {"indices", accessor(d.corners.size(), 5125, "SCALAR")},
                    {"extensions",
                     {{"KHR_draco_mesh_compression",
                       {{"bufferView", view},
                        {"attributes", {{"POSITION", encoded.position},
                                        {"NORMAL", encoded.normal},
                                        {"TEXCOORD_0", encoded.uv}}}}}}}};
    }, {{"mesh", 0}}, glb);
}

// The dome as gltfpack writes a file: each attribute and the indices a buffer view over a
// fallback buffer with no bytes, its EXT_meshopt_compression naming the compressed bytes in the
// file's buffer; the normals octahedral-filtered into 8-bit components (a KHR_mesh_quantization
// accessor). `damage`: the compressed bytes overwritten. `glb`: as a .glb, the compressed bytes
// in its BIN chunk (buffer 0) and the fallback buffer 1, as gltfpack writes it.
inline std::string meshopt_dome(bool damage = false, bool glb = false) {
    std::size_t fallback = 0; // bytes of the fallback buffer the views cover
    const std::string text = dome_file([&](GltfBuilder& b, const Dome& d) {
        const std::size_t n = d.xyz.size() / 3;
        // A view over the fallback buffer whose bytes are `raw` compressed as `mode`.
        const auto compressed = [&](const void* raw, std::size_t count, std::size_t stride,
                                    const char* mode, const char* filter) {
            std::vector<unsigned char> packed;
            if (std::string(mode) == "TRIANGLES") {
                packed.resize(meshopt_encodeIndexBufferBound(count, n));
                packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(),
                                                        static_cast<const unsigned*>(raw), count));
            } else {
                packed.resize(meshopt_encodeVertexBufferBound(count, stride));
                packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), raw, count, stride));
            }
            if (damage) std::fill(packed.begin() + 1, packed.end(), 0xff);
            const int source = b.view(packed.data(), packed.size());
            json view = {{"buffer", 1}, {"byteOffset", fallback}, {"byteLength", count * stride},
                         {"extensions", {{"EXT_meshopt_compression",
                                          {{"buffer", 0},
                                           {"byteOffset", b.doc["bufferViews"][source]["byteOffset"]},
                                           {"byteLength", packed.size()},
                                           {"byteStride", stride},
                                           {"count", count},
                                           {"mode", mode},
                                           {"filter", filter}}}}}};
            if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
            fallback += (count * stride + 3) / 4 * 4;
            b.doc["bufferViews"].push_back(view);
            return static_cast<int>(b.doc["bufferViews"].size() - 1);
        };
        const auto accessor = [&](int view, std::size_t count, int component, const char* type,
                                  bool normalized) {
            b.doc["accessors"].push_back({{"bufferView", view}, {"componentType", component},
                                          {"count", count}, {"type", type}, {"normalized", normalized}});
            return static_cast<int>(b.doc["accessors"].size() - 1);
        };
        std::vector<float> normal4;
        for (std::size_t i = 0; i < n; ++i)
            normal4.insert(normal4.end(), {d.normal[3 * i], d.normal[3 * i + 1], d.normal[3 * i + 2], 0.0f});
        std::vector<std::int8_t> octahedral(4 * n);
        meshopt_encodeFilterOct(octahedral.data(), n, 4, 8, normal4.data());
        b.doc["extensionsUsed"].push_back("EXT_meshopt_compression");
        b.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
        b.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        return json{{"attributes",
                     {{"POSITION", accessor(compressed(d.xyz.data(), n, 12, "ATTRIBUTES", "NONE"), n, 5126, "VEC3", false)},
                      {"NORMAL", accessor(compressed(octahedral.data(), n, 4, "ATTRIBUTES", "OCTAHEDRAL"), n, 5120, "VEC3", true)},
                      {"TEXCOORD_0", accessor(compressed(d.uv.data(), n, 8, "ATTRIBUTES", "NONE"), n, 5126, "VEC2", false)}}},
                    {"indices", accessor(compressed(d.corners.data(), d.corners.size(), 4, "TRIANGLES", "NONE"),
                                         d.corners.size(), 5125, "SCALAR", false)}};
    }, {{"mesh", 0}}, glb);
    const json fallback_buffer = {{"byteLength", fallback},
                                  {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    if (!glb) {
        json doc = json::parse(text);
        doc["buffers"].push_back(fallback_buffer);
        return doc.dump();
    }
    // The GLB's JSON chunk gains the buffer; its BIN chunk stays as it is.
    const auto u32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(text[at + static_cast<std::size_t>(i)]);
        return v;
    };
    const std::size_t json_length = u32(12), bin_at = 20 + json_length;
    json doc = json::parse(text.substr(20, json_length));
    doc["buffers"].push_back(fallback_buffer);
    return GltfBuilder::glb_of(doc.dump(), text.substr(bin_at + 8, u32(bin_at)));
}

// A 4 × 4 image of sixteen colours, as RGB bytes.
inline std::vector<std::uint8_t> checker_pixels() {
    std::vector<std::uint8_t> rgb;
    for (int i = 0; i < 16; ++i)
        rgb.insert(rgb.end(), {static_cast<std::uint8_t>(16 * i), static_cast<std::uint8_t>(255 - 9 * i),
                               static_cast<std::uint8_t>(i % 2 ? 200 : 40)});
    return rgb;
}

// The quad (tests/gltf_models.h) textured with the sixteen colours: as a PNG, or (`webp`) as a
// lossless WebP that only EXT_texture_webp names.
inline GltfBuilder webp_quad(bool webp) {
    GltfBuilder b;
    const std::vector<std::uint8_t> rgb = checker_pixels();
    if (webp) {
        std::uint8_t* encoded = nullptr;
        const std::size_t size = WebPEncodeLosslessRGB(rgb.data(), 4, 4, 12, &encoded);
        if (size == 0) throw std::runtime_error("libwebp encoded nothing");
        const int view = b.view(encoded, size);
        WebPFree(encoded);
        b.doc["images"].push_back({{"bufferView", view}, {"mimeType", "image/webp"}});
        b.doc["samplers"].push_back({{"magFilter", 9728}});
        b.doc["textures"].push_back(
            {{"sampler", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}});
        b.doc["extensionsUsed"] = {"EXT_texture_webp"};
        b.doc["extensionsRequired"] = {"EXT_texture_webp"};
    } else {
        Image image(4, 4);
        std::copy(rgb.begin(), rgb.end(), image.rgb.begin());
        b.texture(encode_png(image), {{"magFilter", 9728}});
    }
    b.doc["materials"].push_back({{"pbrMetallicRoughness",
                                   {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}});
    b.node({{"mesh", quad(b, 0)}});
    camera_on_z(b);
    light_at(b, {0, 0, 4});
    return b;
}

} // namespace glint::testing
