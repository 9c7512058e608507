// The box [-1, 1]³; normal along the axis of the face that was hit.
#pragma once

#include "trace/shapes/shape.h"

#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {

// Face numbering: part = 2·axis + (1 for the +1 face, 0 for the −1 face).
inline ShapeHit intersect_box(const Ray& ray, Real t_max) {
    Real t_near = -kInfinity, t_far = kInfinity;
    std::uint32_t near_face = 0, far_face = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const Real o = ray.origin[axis];
        const Real d = ray.direction[axis];
        if (d == 0) {
            if (o < -1.0_r || o > 1.0_r) return {}; // parallel to this slab and outside it
            continue;
        }
        Real t0 = (-1.0_r - o) / d;
        Real t1 = (1.0_r - o) / d;
        std::uint32_t face0 = 2 * axis, face1 = 2 * axis + 1;
        if (t0 > t1) {
            std::swap(t0, t1);
            std::swap(face0, face1);
        }
        if (t0 > t_near) t_near = t0, near_face = face0;
        if (t1 < t_far) t_far = t1, far_face = face1;
    }
    if (t_near > t_far) return {};
    const ShapeHit entry = candidate(t_near, t_max, near_face);
    return entry.found() ? entry : candidate(t_far, t_max, far_face);
}

inline SurfaceSample box_surface(Vec3 p, std::uint32_t face) {
    const int axis = static_cast<int>(face / 2);
    const Real side = (face % 2) ? 1.0_r : -1.0_r;
    Vec3 error = gamma(3) * glm::abs(p);
    p[axis] = side; // exact on the face
    error[axis] = 0.0_r;
    Vec3 normal(0.0_r);
    normal[axis] = side;
    return {p, normal, error};
}

// The box in the shape table (trace/shapes/table.h).
struct Box {
    static constexpr std::string_view name = "box";
    static constexpr ShapeTraits traits{.convex = true, .keys = {}};

    static ObjectBox bounds(const SceneObject&, const std::vector<TriangleMesh>&) {
        return {DVec3(-1.0), DVec3(1.0)};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams&, const Ray& ray, Real t_max, Counters&) {
        return intersect_box(ray, t_max);
    }
    static SurfaceSample surface(const ShapeParams&, Vec3 p, const Hit& hit) {
        return box_surface(p, hit.primitive);
    }
    // Its own 12 triangles: exact.
    static Tessellation tessellate(float, bool, int) {
        TessellationBuilder b;
        for (int corner = 0; corner < 8; ++corner)
            b.vertex({corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0});
        const std::uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
        for (const auto& f : faces) b.quad(f[0], f[1], f[2], f[3]);
        return b.mesh;
    }
};

} // namespace GLINT_PRECISION
} // namespace glint
