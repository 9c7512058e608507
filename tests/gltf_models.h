// Small glTF models made in memory for the tests and the glTF fuzzer's seeds
// (tests/gltf_seeds.cpp): a textured quad, a dome, a camera and a light made with GltfBuilder.
#pragma once

#include "gltf_builder.h"

#include "io/png.h"
#include "trace/image.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <functional>

namespace glint::testing {

using json = nlohmann::json;

// A PNG of one colour, w × h.
inline std::string solid_png(std::uint8_t r, std::uint8_t g, std::uint8_t b, int w = 1, int h = 1) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = r, p[1] = g, p[2] = b;
        }
    return encode_png(image);
}

// A quad from (−1, −1) to (1, 1) in z = 0, counter-clockwise seen from +z unless `reversed`;
// TEXCOORD_0 (0, 0)…(1, 1), and TEXCOORD_1 where `uv1` is given.
inline int quad(GltfBuilder& b, int material, bool reversed = false, const std::vector<float>& uv1 = {}) {
    const std::vector<std::uint32_t> corners = reversed
                                                   ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                                                   : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    const int mesh = b.mesh({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, corners, material,
                            {0, 1, 1, 1, 1, 0, 0, 0});
    if (!uv1.empty())
        b.doc["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_1"] =
            b.floats(uv1, "VEC2", 2);
    return mesh;
}

// A camera on +z looking down −z at the origin, 5 away.
inline void camera_on_z(GltfBuilder& b) {
    b.doc["cameras"].push_back(
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}}}});
    b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
}

// One white point light at `at`.
inline void light_at(GltfBuilder& b, std::array<double, 3> at) {
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "point"}, {"intensity", 1.0}}});
    b.doc["extensionsUsed"].push_back("KHR_lights_punctual");
    b.node({{"translation", at}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

// An accessor of integers of type T (`component`: the glTF component type), normalized or not.
template <class T>
inline int integers(GltfBuilder& b, const std::vector<T>& values, int component, const char* type,
             int width, bool normalized) {
    const int v = b.view(values.data(), values.size() * sizeof(T));
    b.doc["accessors"].push_back({{"bufferView", v},
                                  {"componentType", component},
                                  {"count", values.size() / static_cast<std::size_t>(width)},
                                  {"type", type},
                                  {"normalized", normalized}});
    return static_cast<int>(b.doc["accessors"].size() - 1);
}

// A dome, z = 0.3(1 − x² − y²) rounded to 1/1024, on a 9 × 9 grid over [−1, 1]², its normals
// exact, its texture coordinates 0 or 1 at the corners of each cell.
struct Dome {
    std::vector<float> xyz, normal, uv;
    std::vector<std::uint32_t> corners;
};
inline Dome dome() {
    Dome d;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
            const double x = (i - 4) / 4.0, y = (j - 4) / 4.0;
            const double z = std::round(0.3 * (1 - x * x - y * y) * 1024) / 1024;
            d.xyz.insert(d.xyz.end(), {float(x), float(y), float(z)});
            const glm::dvec3 n = glm::normalize(glm::dvec3(0.6 * x, 0.6 * y, 1));
            d.normal.insert(d.normal.end(), {float(n.x), float(n.y), float(n.z)});
            d.uv.insert(d.uv.end(), {float(i % 2), float(j % 2)});
        }
    for (std::uint32_t j = 0; j < 8; ++j)
        for (std::uint32_t i = 0; i < 8; ++i) {
            const std::uint32_t a = 9 * j + i;
            d.corners.insert(d.corners.end(), {a, a + 1, a + 10, a, a + 10, a + 9});
        }
    return d;
}

// The dome's file (.gltf, or .glb where `glb`): textured, seen from +z under one light, its
// primitive's JSON (without the material) made by `primitive`, its node `node`.
using DomePrimitive = std::function<json(GltfBuilder&, const Dome&)>;
inline std::string dome_file(const DomePrimitive& primitive, json node = {{"mesh", 0}},
                             bool glb = false) {
    GltfBuilder b;
    b.doc["extensionsUsed"] = json::array();
    const int texture = b.texture(solid_png(200, 160, 90, 2, 2));
    b.doc["materials"].push_back({{"pbrMetallicRoughness",
                                   {{"baseColorTexture", {{"index", texture}}}, {"metallicFactor", 0.0}}}});
    json p = primitive(b, dome());
    p["material"] = 0;
    b.doc["meshes"].push_back({{"primitives", json::array({p})}});
    b.node(node);
    camera_on_z(b);
    light_at(b, {1, 2, 4});
    return glb ? b.glb() : b.gltf();
}
// Its primitive as floats.
inline json plain_dome(GltfBuilder& b, const Dome& d) {
    return {{"attributes", {{"POSITION", b.floats(d.xyz, "VEC3", 3)},
                            {"NORMAL", b.floats(d.normal, "VEC3", 3)},
                            {"TEXCOORD_0", b.floats(d.uv, "VEC2", 2)}}},
            {"indices", b.indices(d.corners)}};
}

} // namespace glint::testing
