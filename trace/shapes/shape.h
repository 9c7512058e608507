// What every unit primitive answers: where a ray first crosses it (object space), and the
// surface there (point projected back onto the surface, outward normal, error bound); and the
// facts about a shape that the loaders, the World and the item buffer read from its type
// (trace/shapes/table.h).
#pragma once

#include "trace/math.h"
#include "trace/ray.h"
#include "trace/scene.h"
#include "trace/shapes/tessellation.h"

#include <algorithm>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

// Object-space [lo, hi], in double (the scene's precision).
using ObjectBox = std::pair<DVec3, DVec3>;

// How the item buffer draws a shape (raster/item_buffer.cpp).
enum class RasterAs : std::uint8_t {
    tessellated, // its `tessellate` (tessellated modes), or its proxy box (proxy mode)
    analytic,    // always its exact intersection in shaders/item_proxy.frag (unbounded shapes)
    triangles,   // its own mesh, exact as it is
};

// The optional keys of a scene file's object that a shape accepts (docs/SCENES.md).
struct ShapeKeys {
    bool top_radius = false;
    bool open = false;
    bool vertices = false; // with no `indices` as well: the shape is one triangle of 3 vertices
    bool indices = false;
    bool file = false; // an OBJ file
};

struct ShapeTraits {
    // A ray leaving the surface on the outward side cannot meet the shape again (the spawn rule,
    // World::surface)...
    bool convex = false;
    // ... nor on either side.
    bool planar = false;
    // The checker (docs/SCENES.md) uses x and z only, in the shape's plane (planes, disks).
    bool checker_in_plane = false;
    RasterAs raster = RasterAs::tessellated;
    // Whether shaders/item_proxy.frag intersects it exactly; proxy mode draws the tessellation
    // of a tessellated shape that it does not.
    bool in_proxy_shader = true;
    ShapeKeys keys;
};

// Which of a mesh's hits are no hits, as its intersection reads it: where the material cuts out
// (DESIGN §13, docs/SCENES.md "Cut-outs"), a triangle's hit whose alpha, `alpha` × the texture's
// alpha at the hit's texture coordinates (where the mesh has them), is below `cutoff`; where it
// is one-sided (DESIGN §14), a triangle seen from behind.
struct CutOut {
    bool cuts = true;                 // the alpha test applies
    const Texture* texture = nullptr; // the base colour texture, or none
    float alpha = 1.0f;
    float cutoff = 0.5f;
    // One-sided faces: only hits on a triangle's counter-clockwise side in object space (its
    // winding normal towards the ray: mesh.h, seen_from_behind) count. Tested in object space,
    // this is the side the placed normal M⁻ᵀn faces whatever M's determinant: the winding glTF
    // flips under a negative determinant is the winding seen in the world.
    bool one_sided = false;
};

inline namespace GLINT_PRECISION {

struct Mesh;

// What a shape's intersection and surface read of their object besides the ray.
struct ShapeParams {
    Real top_radius = 0;        // cones
    bool open = false;          // cylinders and cones without caps
    const Mesh* mesh = nullptr; // triangles and meshes
    const CutOut* cut_out = nullptr; // a triangle or mesh whose material cuts out, or none
};

struct ShapeHit {
    Real t = kInfinity;
    std::uint32_t part = 0; // box face, cylinder/cone side or cap, triangle index
    // Where on the part, when the surface needs it from the intersection: a triangle's
    // barycentric weights of its vertices 1 and 2 (0 for the other shapes).
    Real u = 0, v = 0;

    bool found() const { return t != kInfinity; }
};

// What a query wants of a shape: its nearest hit in (0, t_max), or any hit there (a shadow
// ray's question), which a mesh may answer at the first leaf of its tree that holds one. Both
// find a hit exactly when there is one.
enum class Wanted : std::uint8_t { nearest, any };

// A point on a unit primitive in object space.
struct SurfaceSample {
    Vec3 point;  // on the surface up to `error`
    Vec3 normal; // unit, outward
    Vec3 error;  // per-component bound on |point − exact surface point|
    // What shading uses when it differs from `normal` (a mesh's interpolated vertex normals,
    // not necessarily unit), else zero.
    Vec3 shading{0.0_r};
};

// The nearer of two candidate hits; on equal t the first wins, keeping results deterministic.
inline ShapeHit closer(ShapeHit a, ShapeHit b) {
    return b.t < a.t ? b : a;
}

// A candidate t counts when it lies in the open interval (0, t_max).
inline ShapeHit candidate(Real t, Real t_max, std::uint32_t part) {
    return (t > 0 && t < t_max) ? ShapeHit{t, part} : ShapeHit{};
}

} // namespace GLINT_PRECISION
} // namespace glint
