// A pixel's ray tree as shading walks it (`glint explain`, the preview's click): trace/shading.cpp
// reports each ray it casts, each surface it shades and each light's terms to a RayRecorder when
// the pixel's RayTree carries one. Nothing is recomputed here: the explanation is the render's own
// arithmetic, written down as it happens (trace/explain.h adds what a reader needs around it).
#pragma once

#include "trace/texture.h"

#include "trace/names.h"
#include "trace/world.h"

#include <vector>

namespace glint {

// The rays of a ray tree that are nodes of it; shadow rays are per light, below a node.
enum class RayKind : std::uint8_t { primary, reflection, transmission };

template <> struct EnumNames<RayKind> {
    static constexpr auto names = name_table("primary", "reflection", "transmission");
};

inline namespace GLINT_PRECISION {

// One light at a shaded surface point.
struct LightTerm {
    std::uint32_t light = 0;
    Real n_dot_l = 0; // ≤ 0: the light is behind the surface, no shadow ray, no terms
    Real through = 0; // the light's fraction that arrives: 1 lit, 0 blocked, else glass
    std::uint64_t shadow_rays = 0; // segments cast (1 + glass crossings followed)
    Vec3 diffuse{0}, specular{0}; // the terms added: through · colour · k_d(n·l), … k_s(r·v)^n
    bool in_front() const { return n_dot_l > 0; }
};

// A reflected or transmitted ray the tree did not cast, and why.
struct OmittedRay {
    RayKind kind;
    Real weight; // the path weight it would have carried
    enum class Why : std::uint8_t { max_depth, min_weight, tree_budget } why;
};

// One node: a primary, reflected or transmitted ray, what it hit and what it brought back.
struct RecordedRay {
    RayKind kind = RayKind::primary;
    int parent = -1; // index in RayRecorder::rays(); -1 for the primary ray
    int depth = 0;   // reflections and transmissions before it
    Real factor = 1; // the parent's reflectivity or transmission that weights this ray's colour
    Real weight = 1; // the path weight: the product of the factors down to here
    Ray ray;         // camera-relative world space (World's)
    Hit hit;
    // At a hit (hit.found()):
    SurfacePoint surface;
    bool odd_cell = false; // the checker's odd cell: its colours replaced the material's
    // The base colour texture's lookup, where the material has one and the mesh coordinates.
    std::optional<TexelSample> texel;
    Vec3 ambient{0};       // k_a · I_a
    Vec3 emission{0};      // E: the material's emission there (DESIGN §13)
    std::vector<LightTerm> lights;
    std::vector<int> children; // reflected, then transmitted
    std::vector<OmittedRay> omitted;
    Vec3 colour{0}; // R_p, unclamped: what the ray brought back
};

// Receives shade()'s reports, in the order it makes them. One recorder explains one sample.
class RayRecorder {
  public:
    // A ray was cast (the primary ray by shade_pixel, the others by shade()); it is open until
    // `end` reports its colour, and what is reported meanwhile belongs to it.
    void begin(RayKind kind, const Ray& ray, const Hit& hit, Real factor, Real weight, int depth);
    void end(Vec3 colour);
    void surface(const SurfacePoint& point, bool odd_cell, const std::optional<TexelSample>& texel,
                 Vec3 ambient, Vec3 emission);
    void light(const LightTerm& term);
    void omitted(RayKind kind, Real weight, OmittedRay::Why why);

    const std::vector<RecordedRay>& rays() const { return rays_; }

  private:
    RecordedRay& open();
    std::vector<RecordedRay> rays_;
    std::vector<int> open_; // the path from the primary ray to the ray being shaded
};

} // namespace GLINT_PRECISION
} // namespace glint
