#include "io/gltf_materials.h"

#include "io/error.h"
#include "io/texture_file.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

// A warning's reason is printed whole (DESIGN §14), however long the path in it.
constexpr std::size_t kWhole = std::string::npos;

} // namespace

GltfMaterials::GltfMaterials(const tinygltf::Model& model, const std::string& name,
                             const ModelFiles& files, const ModelOptions& options, Scene& scene,
                             Unused unused)
    : m_(model), name_(name), files_(files), options_(options), scene_(scene),
      unused_(std::move(unused)) {
    scene_.materials.emplace_back();
    scene_.material_names.emplace_back("default");
    places_.emplace_back("the default material");
}

void GltfMaterials::fail(const std::string& place, const std::string& what) const {
    throw SceneError(name_ + ": " + place + ": " + what);
}

// glTF material `index` in glint's Phong (docs/SCENES.md, "glTF materials"), made once.
std::uint32_t GltfMaterials::material(int index) {
    if (const auto it = materials_.find(index); it != materials_.end()) return it->second;
    const tinygltf::Material& g = m_.materials[static_cast<std::size_t>(index)];
    const std::string at = pointer("materials", static_cast<std::size_t>(index));
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    const std::string pbr_at = at + "/pbrMetallicRoughness";
    if (pbr.baseColorFactor.size() != 4) fail(pbr_at + "/baseColorFactor", "must have 4 numbers");
    const auto unit = [&](double v, const std::string& where) {
        if (!(v >= 0 && v <= 1)) fail(where, "must be between 0 and 1");
        return v;
    };
    glm::dvec3 base;
    for (int c = 0; c < 3; ++c)
        base[c] = unit(pbr.baseColorFactor[static_cast<std::size_t>(c)],
                       pbr_at + "/baseColorFactor/" + std::to_string(c));
    const double metallic = unit(pbr.metallicFactor, pbr_at + "/metallicFactor");
    const double roughness = unit(pbr.roughnessFactor, pbr_at + "/roughnessFactor");
    double transmission = 0, ior = 1.5;
    if (const auto it = g.extensions.find("KHR_materials_transmission");
        it != g.extensions.end() && it->second.Has("transmissionFactor"))
        transmission = unit(it->second.Get("transmissionFactor").GetNumberAsDouble(),
                            at + "/extensions/KHR_materials_transmission/transmissionFactor");
    if (const auto it = g.extensions.find("KHR_materials_ior");
        it != g.extensions.end() && it->second.Has("ior"))
        ior = it->second.Get("ior").GetNumberAsDouble();
    Material out;
    MetalRoughInputs& p = out.metal_rough.emplace();
    p.base = glm::vec3(base);
    p.metallic = static_cast<float>(metallic);
    p.roughness = static_cast<float>(roughness);
    p.transmission = static_cast<float>(transmission);
    out.transmission = static_cast<float>(transmission);
    out.ior = static_cast<float>(ior);
    out.double_sided = g.doubleSided;
    if (pbr.baseColorTexture.index >= 0)
        out.texture = texture(pbr.baseColorTexture, pbr_at + "/baseColorTexture", true);
    if (pbr.metallicRoughnessTexture.index >= 0)
        p.metal_rough_texture =
            texture(pbr.metallicRoughnessTexture, pbr_at + "/metallicRoughnessTexture");
    if (g.normalTexture.index >= 0) {
        out.normal_texture = texture(g.normalTexture, at + "/normalTexture");
        if (!(std::abs(g.normalTexture.scale) <= 1e3))
            fail(at + "/normalTexture/scale", "must be a number within ±1000");
        out.normal_scale = static_cast<float>(g.normalTexture.scale);
    }
    if (g.occlusionTexture.index >= 0) {
        p.occlusion_texture = texture(g.occlusionTexture, at + "/occlusionTexture");
        p.occlusion_strength = static_cast<float>(
            unit(g.occlusionTexture.strength, at + "/occlusionTexture/strength"));
    }
    emission(g, at, out);
    alpha_mode(g, at, pbr_at, out);
    phong_of_factors(out);
    if (g.extensions.contains("KHR_materials_unlit")) unlit(out);
    for (const auto& [extension, value] : g.extensions)
        if (!kKnownExtensions.contains(extension)) unused_("extension " + printable(extension), at);
    const auto k = static_cast<std::uint32_t>(scene_.materials.size());
    scene_.materials.push_back(out);
    scene_.material_names.push_back(g.name.empty() ? "material " + std::to_string(index) : g.name);
    places_.push_back(at);
    return materials_.emplace(index, k).first->second;
}

// The Phong colours of a metallic-roughness material with every texel 1 (DESIGN §14's
// formulas on the factors alone): what the preview draws, and shading's inputs where the
// mesh has no texture coordinates.
void GltfMaterials::phong_of_factors(Material& out) {
    const MetalRoughInputs& p = *out.metal_rough;
    const glm::dvec3 b(p.base);
    const double m = p.metallic, r = p.roughness, t = p.transmission, keep = p.coverage;
    const glm::dvec3 diffuse = b * ((1 - m) * (1 - t) * keep);
    const glm::dvec3 specular = (glm::dvec3(0.04 * (1 - m)) + b * m) * keep;
    const double reflectivity = m * (1 - r) * (1 - r) * keep;
    out.diffuse = glm::vec3(diffuse);
    out.specular = glm::vec3(specular);
    out.reflectivity = static_cast<float>(reflectivity);
    out.ambient = glm::vec3(diffuse + specular * (1 - reflectivity));
    const double alpha = r * r;
    out.shininess =
        static_cast<float>(alpha > 0 ? std::clamp(2 / (alpha * alpha) - 2, 1.0, 1e6) : 1e6);
}

// KHR_materials_unlit: the colour is the base colour (× its texture, × COLOR_0), unlit and
// unreflecting; shading reads it as the emission (Material::unlit). A cut-out keeps the base
// texture's alpha; under BLEND the coverage scales the colour and the rest passes straight on.
void GltfMaterials::unlit(Material& out) {
    const MetalRoughInputs& p = *out.metal_rough;
    out.emission = p.base * p.coverage;
    out.emission_texture = out.texture;
    if (out.cut_out && out.alpha_texture == kNoTexture) out.alpha_texture = out.texture;
    out.texture = kNoTexture;
    out.ambient = out.diffuse = out.specular = glm::vec3(0.0f);
    out.reflectivity = 0.0f;
    out.transmission = 1.0f - p.coverage;
    out.normal_texture = kNoTexture;
    out.metal_rough.reset();
    out.unlit = true;
}

// Emission (DESIGN §13): emissiveFactor × emissiveStrength, times the emissive texture.
void GltfMaterials::emission(const tinygltf::Material& g, const std::string& at, Material& out) {
    if (g.emissiveFactor.size() != 3) fail(at + "/emissiveFactor", "must have 3 numbers");
    double strength = 1;
    if (const auto it = g.extensions.find("KHR_materials_emissive_strength");
        it != g.extensions.end() && it->second.Has("emissiveStrength")) {
        strength = it->second.Get("emissiveStrength").GetNumberAsDouble();
        if (!(strength >= 0 && strength <= 1e6))
            fail(at + "/extensions/KHR_materials_emissive_strength/emissiveStrength",
                 "must be between 0 and 1e6");
    }
    for (int c = 0; c < 3; ++c) {
        const double v = g.emissiveFactor[static_cast<std::size_t>(c)];
        if (!(v >= 0 && v <= 1))
            fail(at + "/emissiveFactor/" + std::to_string(c), "must be between 0 and 1");
        out.emission[c] = static_cast<float>(v * strength);
    }
    if (g.emissiveTexture.index >= 0 && out.emission != glm::vec3(0.0f)) {
        out.emission_texture = texture(g.emissiveTexture, at + "/emissiveTexture", true);
        // An emissive texture that cannot be used leaves no emission (DESIGN §14): the
        // factor alone would light the whole surface.
        if (out.emission_texture == kNoTexture) out.emission = glm::vec3(0.0f);
    }
}

// The base colour's alpha (docs/SCENES.md, "Cut-outs and blending"): MASK cuts out where it
// is below alphaCutoff (DESIGN §13); BLEND blends the factor's alpha as a transmission of
// 1 − alpha with ior 1 (a texture's alpha is not blended, with a warning); OPAQUE ignores it.
void GltfMaterials::alpha_mode(const tinygltf::Material& g, const std::string& at,
                               const std::string& pbr_at, Material& out) {
    const double a = g.pbrMetallicRoughness.baseColorFactor[3];
    if (!(a >= 0 && a <= 1)) fail(pbr_at + "/baseColorFactor/3", "must be between 0 and 1");
    if (g.alphaMode == "MASK") {
        if (!(g.alphaCutoff >= 0 && g.alphaCutoff <= 1))
            fail(at + "/alphaCutoff", "must be between 0 and 1");
        out.cut_out = true;
        out.alpha = static_cast<float>(a);
        out.alpha_cutoff = static_cast<float>(g.alphaCutoff);
    } else if (g.alphaMode == "BLEND") {
        if (g.pbrMetallicRoughness.baseColorTexture.index >= 0)
            unused_("a base colour texture's alpha under alphaMode BLEND (the factor's "
                    "alpha blends)",
                    at);
        // What shows of the surface is alpha of it; the rest passes straight through.
        const auto keep = static_cast<float>(a);
        out.metal_rough->coverage = keep;
        out.transmission = 1 - keep * (1 - out.transmission);
        if (a < 1) out.ior = 1;
    } else if (g.alphaMode != "OPAQUE") {
        fail(at + "/alphaMode",
             "must be OPAQUE, MASK or BLEND, not '" + printable(g.alphaMode) + "'");
    }
}

// KHR_texture_transform on a texture reference: uv' = T(offset) · R(rotation) · S(scale) · uv,
// as the extension writes it; its texCoord, where given, overrides the reference's.
glm::mat3 GltfMaterials::uv_transform(const tinygltf::ExtensionMap& extensions,
                                      const std::string& at, int& tex_coord) const {
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end()) return glm::mat3(1.0f);
    const tinygltf::Value& v = it->second;
    const std::string ext_at = at + "/extensions/KHR_texture_transform";
    const auto pair = [&](const char* key, double fallback) {
        glm::dvec2 out(fallback);
        if (!v.Has(key)) return out;
        const tinygltf::Value& a = v.Get(key);
        if (!a.IsArray() || a.ArrayLen() != 2) fail(ext_at + "/" + key, "must have 2 numbers");
        for (int k = 0; k < 2; ++k) {
            out[k] = a.Get(k).GetNumberAsDouble();
            if (!(std::abs(out[k]) <= 1e6))
                fail(ext_at + "/" + key + "/" + std::to_string(k), "must be a number within ±1e6");
        }
        return out;
    };
    const glm::dvec2 offset = pair("offset", 0), scale = pair("scale", 1);
    double rotation = 0;
    if (v.Has("rotation")) {
        rotation = v.Get("rotation").GetNumberAsDouble();
        if (!(std::abs(rotation) <= 1e6))
            fail(ext_at + "/rotation", "must be a number within ±1e6");
    }
    if (v.Has("texCoord")) tex_coord = v.Get("texCoord").GetNumberAsInt();
    const double c = std::cos(rotation), s = std::sin(rotation);
    // Columns (glm): the extension's matrix T · R · S.
    glm::dmat3 m(1.0);
    m[0] = {c * scale.x, -s * scale.x, 0};
    m[1] = {s * scale.y, c * scale.y, 0};
    m[2] = {offset.x, offset.y, 1};
    return glm::mat3(m);
}

// The texture `info` names (at `at`), or kNoTexture (with a warning) where it cannot be used;
// its image decoded once however many textures sample it. `colour`: its texels are colours
// (sRGB-encoded, as glTF says: decoded under --colour srgb), not data such as normals.
template <class Info>
std::uint32_t GltfMaterials::texture(const Info& info, const std::string& at, bool colour) {
    if (static_cast<std::size_t>(info.index) >= m_.textures.size())
        fail(at + "/index", "no texture " + std::to_string(info.index));
    int tex_coord = info.texCoord;
    const glm::mat3 transform = uv_transform(info.extensions, at, tex_coord);
    const tinygltf::Texture& t = m_.textures[static_cast<std::size_t>(info.index)];
    const std::string texture_at = pointer("textures", static_cast<std::size_t>(info.index));
    // EXT_texture_webp's image where it names one (its fallback, `source`, may be absent).
    int source = t.source;
    std::string source_at = texture_at + "/source";
    if (const auto it = t.extensions.find("EXT_texture_webp"); it != t.extensions.end()) {
        source_at = texture_at + "/extensions/EXT_texture_webp/source";
        const tinygltf::Value& webp = it->second.Get("source");
        if (!webp.IsInt()) fail(source_at, "must be an image index");
        source = webp.GetNumberAsInt();
    }
    if (source < 0) {
        unused_("textures without an image source", texture_at);
        return kNoTexture;
    }
    if (static_cast<std::size_t>(source) >= m_.images.size())
        fail(source_at, "no image " + std::to_string(source));
    if (tex_coord != 0 && tex_coord != 1) {
        scene_.warnings.push_back(name_ + ": " + at + ": texture not used: image '" +
                                  printable(image_label(source), kWhole) +
                                  "' is read through TEXCOORD_" + std::to_string(tex_coord) +
                                  ", and glint reads TEXCOORD_0 and TEXCOORD_1");
        return kNoTexture;
    }
    Texture out;
    if (t.sampler >= 0) {
        if (static_cast<std::size_t>(t.sampler) >= m_.samplers.size())
            fail(texture_at + "/sampler", "no sampler " + std::to_string(t.sampler));
        const tinygltf::Sampler& s = m_.samplers[static_cast<std::size_t>(t.sampler)];
        const std::string sampler_at = pointer("samplers", static_cast<std::size_t>(t.sampler));
        out.wrap_s = wrap(s.wrapS, sampler_at + "/wrapS");
        out.wrap_t = wrap(s.wrapT, sampler_at + "/wrapT");
    }
    out.image = image(source);
    out.uv_transform = transform;
    out.srgb = colour && options_.srgb;
    out.set = tex_coord;
    if (!out.image) return kNoTexture;
    scene_.textures.push_back(out);
    return static_cast<std::uint32_t>(scene_.textures.size() - 1);
}

Wrap GltfMaterials::wrap(int mode, const std::string& at) const {
    switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
        return Wrap::repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
        return Wrap::clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
        return Wrap::mirror;
    default:
        fail(at, "unknown wrap mode " + std::to_string(mode));
    }
}

// How messages name image `index`: its URI (decoded), else its name or number.
std::string GltfMaterials::image_label(int index) const {
    const tinygltf::Image& g = m_.images[static_cast<std::size_t>(index)];
    if (!g.uri.empty() && !is_data_uri(g.uri)) return decode_uri(g.uri);
    return g.name.empty() ? "image " + std::to_string(index) : g.name;
}

std::shared_ptr<const TextureImage> GltfMaterials::image(int index) {
    if (const auto it = images_.find(index); it != images_.end()) return it->second;
    const tinygltf::Image& g = m_.images[static_cast<std::size_t>(index)];
    const std::string at = pointer("images", static_cast<std::size_t>(index));
    const std::string label = image_label(index);
    std::string why;
    std::optional<TextureImage> decoded;
    if (!g.image.empty()) {
        decoded = decode_texture(std::string(g.image.begin(), g.image.end()), label, why);
    } else if (!g.uri.empty() && !is_data_uri(g.uri)) {
        if (const std::optional<std::string> bytes = files_(decode_uri(g.uri), why))
            decoded = decode_texture(*bytes, label, why);
        else
            why = "cannot read '" + printable(label, kWhole) + "': " + why;
    } else {
        why = "it holds no image";
    }
    std::shared_ptr<const TextureImage> out;
    if (decoded)
        out = std::make_shared<const TextureImage>(std::move(*decoded));
    else
        scene_.warnings.push_back(name_ + ": " + at +
                                  ": texture not used: " + printable(why, kWhole));
    return images_.emplace(index, out).first->second;
}

} // namespace glint
