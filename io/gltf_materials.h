// A glTF model's materials as glint's (docs/SCENES.md, "glTF"; DESIGN §13, §14): the
// metallic-roughness inputs each hit reads per texel, alpha modes, emission, normal maps, and
// the textures they sample, each image decoded once. io/gltf_loader.cpp asks for a material
// when a primitive first names it.
#pragma once

#include "io/gltf_container.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace glint {

class GltfMaterials {
  public:
    // `unused(feature, place)`: a feature of the file glint renders without (one warning lists
    // them).
    using Unused = std::function<void(const std::string& feature, const std::string& place)>;

    // Adds glint's default material to `scene` (index 0: for primitives with no material).
    GltfMaterials(const tinygltf::Model& model, const std::string& name, const ModelFiles& files,
                  const ModelOptions& options, Scene& scene, Unused unused);

    // glTF material `index` (an index the model has) as glint's, made on first use: its index
    // in scene.materials. Textures go to scene.textures, warnings to scene.warnings.
    std::uint32_t material(int index);

    // Where scene material k came from, for messages: "/materials/2", or the default.
    const std::string& place(std::size_t k) const { return places_.at(k); }

  private:
    [[noreturn]] void fail(const std::string& place, const std::string& what) const;
    static void phong_of_factors(Material& out);
    static void unlit(Material& out);
    void emission(const tinygltf::Material& g, const std::string& at, Material& out);
    void alpha_mode(const tinygltf::Material& g, const std::string& at, const std::string& pbr_at,
                    Material& out);
    glm::mat3 uv_transform(const tinygltf::ExtensionMap& extensions, const std::string& at,
                           int& tex_coord) const;
    template <class Info>
    std::uint32_t texture(const Info& info, const std::string& at, bool colour = false);
    Wrap wrap(int mode, const std::string& at) const;
    std::string image_label(int index) const;
    std::shared_ptr<const TextureImage> image(int index);

    const tinygltf::Model& m_;
    const std::string& name_;
    const ModelFiles& files_;
    const ModelOptions& options_;
    Scene& scene_;
    Unused unused_;
    std::map<int, std::uint32_t> materials_;
    std::map<int, std::shared_ptr<const TextureImage>> images_;
    std::vector<std::string> places_; // by scene material
};

} // namespace glint
