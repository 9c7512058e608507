// The closed set of shapes, in one table. Each shape is one type in its own file here, holding
// everything glint knows of it: its name, traits (trace/shapes/shape.h: convexity for the spawn
// rule, how the item buffer draws it, which scene keys it takes), object-space bounds,
// intersection, surface and conservative tessellation. Everything else reaches a shape through
// `visit_shape` or the tables below, never by naming it.
//
// Adding a shape: its file, then an entry in each of the four lists here (enumerator, name,
// include, type); the static_assert below holds them in step. The proxy shader's SHAPE_ constants
// come from `names` (raster/item_buffer.cpp, with_shape_constants); a shape the shader does not
// intersect says so in its traits (in_proxy_shader = false) and proxy mode draws its
// tessellation instead.
//
// The names, traits, bounds and tessellations do not depend on the tracer's precision; the
// loaders (glint_io) read them through the same types.
#pragma once

#include "trace/names.h"

#include <cstdint>

namespace glint {

// One per type in `Shapes` below, in the same order.
enum class ShapeKind : std::uint8_t { sphere, plane, box, disk, cylinder, cone, triangle, mesh };

} // namespace glint

#include "trace/shapes/box.h"
#include "trace/shapes/cone.h"
#include "trace/shapes/cylinder.h"
#include "trace/shapes/mesh.h"
#include "trace/shapes/plane.h"
#include "trace/shapes/sphere.h"

#include <array>
#include <type_traits>

namespace glint {

template <class... S> struct ShapeList {};

// The scene files' names, as the shapes' types give them (checked below).
template <> struct EnumNames<ShapeKind> {
    static constexpr auto names =
        name_table("sphere", "plane", "box", "disk", "cylinder", "cone", "triangle", "mesh");
};

inline namespace GLINT_PRECISION {

using Shapes = ShapeList<Sphere, Plane, Box, Disk, Cylinder, Cone, Triangle, MeshShape>;

namespace detail {

template <class F, class First, class... Rest> decltype(auto) visit_from(std::size_t index, F&& f) {
    if constexpr (sizeof...(Rest) == 0) {
        return f(First{});
    } else {
        if (index == 0) return f(First{});
        return visit_from<F, Rest...>(index - 1, std::forward<F>(f));
    }
}

template <class... S> constexpr bool names_match(ShapeList<S...>) {
    std::size_t i = 0;
    return ((S::name == EnumNames<ShapeKind>::names[i++]) && ...) &&
           sizeof...(S) == EnumNames<ShapeKind>::names.size();
}

template <class... S> constexpr auto traits_of(ShapeList<S...>) {
    return std::array<ShapeTraits, sizeof...(S)>{S::traits...};
}

} // namespace detail

static_assert(detail::names_match(Shapes{}),
              "ShapeKind, its names and Shapes must list the same shapes in the same order");

// f(S{}) for the type S of `kind`: every overload must return the same type. The chain of
// comparisons compiles to a jump table or a few branches; either inlines into the caller.
template <class F> decltype(auto) visit_shape(ShapeKind kind, F&& f) {
    return [&]<class... S>(ShapeList<S...>) -> decltype(auto) {
        return detail::visit_from<F, S...>(static_cast<std::size_t>(kind), std::forward<F>(f));
    }(Shapes{});
}

inline constexpr auto kShapeTraits = detail::traits_of(Shapes{});

inline constexpr const ShapeTraits& shape_traits(ShapeKind kind) {
    return kShapeTraits[static_cast<std::size_t>(kind)];
}

// The object-space box of an object's primitive; nothing for shapes without one (planes).
inline std::optional<ObjectBox> unit_box(const SceneObject& object,
                                         const std::vector<TriangleMesh>& meshes) {
    return visit_shape(object.shape, [&](auto shape) -> std::optional<ObjectBox> {
        return decltype(shape)::bounds(object, meshes);
    });
}

// Objects' unit boxes where many objects may place one mesh (instances): each mesh's box is
// found once, on first use, rather than from all its vertices for every object that places it.
class UnitBoxes {
  public:
    explicit UnitBoxes(const std::vector<TriangleMesh>& meshes)
        : meshes_(meshes), mesh_boxes_(meshes.size()) {}
    std::optional<ObjectBox> operator()(const SceneObject& object) {
        if (object.shape != ShapeKind::mesh || object.mesh >= mesh_boxes_.size())
            return unit_box(object, meshes_);
        std::optional<ObjectBox>& box = mesh_boxes_[object.mesh];
        if (!box) box = unit_box(object, meshes_);
        return box;
    }

  private:
    const std::vector<TriangleMesh>& meshes_;
    std::vector<std::optional<ObjectBox>> mesh_boxes_;
};

// The conservative tessellation of a tessellated shape (RasterAs::tessellated) at `n` segments
// around each curved outline; empty for the others.
inline Tessellation tessellate_shape(ShapeKind kind, float top_radius, bool open, int n) {
    return visit_shape(kind, [&]<class S>(S) {
        if constexpr (requires { S::tessellate(top_radius, open, n); })
            return S::tessellate(top_radius, open, n);
        else
            return Tessellation{};
    });
}

} // namespace GLINT_PRECISION
} // namespace glint
