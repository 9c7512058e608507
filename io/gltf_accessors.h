// A parsed glTF model's accessors read for glint (docs/SCENES.md, "glTF"): every bound checked
// (the accessor against its buffer view, the view against its buffer, the stride, the sparse
// indices) before a byte is read, each component converted to double, normalized integers
// scaled; a failure names the file and the JSON pointer. Shared by the mesh, material and
// animation readers (io/gltf_loader.cpp, io/gltf_animation.cpp).
#pragma once

#include "io/gltf_container.h"

#include <initializer_list>
#include <string>
#include <vector>

namespace glint {

class GltfAccessors {
  public:
    GltfAccessors(const tinygltf::Model& model, const std::string& name) : m_(model), name_(name) {}

    // Accessor `index`, named by `use` (where it is referred to), read as `width` components per
    // element, each converted to double: every bound checked first, sparse values applied.
    std::vector<double> read_accessor(int index, int type, int width,
                                      std::initializer_list<int> component_types,
                                      const std::string& use, std::size_t max_count) const;

    // Throws SceneError "NAME: PLACE: WHAT".
    [[noreturn]] void fail(const std::string& place, const std::string& what) const;
    const std::string& name() const { return name_; }
    // The bytes of one component of glTF component type `type`; 0 for a type glint does not read.
    static int component_bytes(int type);

  private:
    static double component(const unsigned char* p, int type, bool normalized);
    // The bytes of buffer view `view` from `offset`, for `count` elements of `element` bytes
    // `stride` apart: checked against the view and its buffer, and returned.
    const unsigned char* view_bytes(int view, std::size_t offset, std::size_t count,
                                    std::size_t element, std::size_t stride,
                                    const std::string& at) const;

    const tinygltf::Model& m_;
    const std::string& name_;
};

} // namespace glint
