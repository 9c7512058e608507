// The plane y = 0 (infinite) and the unit disk y = 0, x²+z² ≤ 1; normal +y.
#pragma once

#include "trace/shapes/shape.h"

namespace glint {
inline namespace GLINT_PRECISION {

inline Real plane_t(const Ray& ray) {
    // A ray parallel to the plane (d.y = 0) gives ±inf or NaN, which candidate() rejects.
    return -ray.origin.y / ray.direction.y;
}

inline ShapeHit intersect_plane(const Ray& ray, Real t_max) {
    return candidate(plane_t(ray), t_max, 0);
}

inline ShapeHit intersect_disk(const Ray& ray, Real t_max) {
    const Real t = plane_t(ray);
    const Vec3 p = ray.origin + t * ray.direction;
    if (p.x * p.x + p.z * p.z > 1.0_r) return {};
    return candidate(t, t_max, 0);
}

inline SurfaceSample plane_surface(Vec3 p) {
    // y is set exactly; x and z come from o + t·d (tangent errors never move p off the plane).
    return {{p.x, 0.0_r, p.z},
            {0.0_r, 1.0_r, 0.0_r},
            gamma(3) * Vec3(std::abs(p.x), 0.0_r, std::abs(p.z))};
}

// The plane and the disk in the shape table (trace/shapes/table.h).
struct Plane {
    static constexpr std::string_view name = "plane";
    static constexpr ShapeTraits traits{
        .planar = true, .checker_in_plane = true, .raster = RasterAs::analytic, .keys = {}};

    // Unbounded: tested by every ray, outside any structure.
    static std::optional<ObjectBox> bounds(const SceneObject&, const std::vector<TriangleMesh>&) {
        return std::nullopt;
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams&, const Ray& ray, Real t_max, Counters&) {
        return intersect_plane(ray, t_max);
    }
    static SurfaceSample surface(const ShapeParams&, Vec3 p, const Hit&) {
        return plane_surface(p);
    }
};

struct Disk {
    static constexpr std::string_view name = "disk";
    static constexpr ShapeTraits traits{.planar = true, .checker_in_plane = true, .keys = {}};

    static ObjectBox bounds(const SceneObject&, const std::vector<TriangleMesh>&) {
        return {DVec3(-1.0, 0.0, -1.0), DVec3(1.0, 0.0, 1.0)};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams&, const Ray& ray, Real t_max, Counters&) {
        return intersect_disk(ray, t_max);
    }
    static SurfaceSample surface(const ShapeParams&, Vec3 p, const Hit&) {
        return plane_surface(p);
    }
    static Tessellation tessellate(float, bool, int n) {
        TessellationBuilder b;
        b.cap(b.ring(n, 0, 1 * (1 + 1e-6)), 0);
        b.mesh.max_deviation = static_cast<float>(circumscribed_reach(n) - 1);
        return b.mesh;
    }
};

} // namespace GLINT_PRECISION
} // namespace glint
