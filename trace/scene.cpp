// Geometry facts about scene objects that the loader (to check them) and World (to place them)
// both need.
#include "trace/scene.h"

#include <algorithm>
#include <limits>

namespace glint {

Bounds unit_bounds(const SceneObject& object, const std::vector<Mesh>& meshes) {
    switch (object.shape) {
    case ShapeKind::sphere:
    case ShapeKind::box:
        return {Vec3(-1.0f), Vec3(1.0f)};
    case ShapeKind::disk:
        return {Vec3(-1.0f, 0.0f, -1.0f), Vec3(1.0f, 0.0f, 1.0f)};
    case ShapeKind::cylinder:
        return {Vec3(-1.0f, 0.0f, -1.0f), Vec3(1.0f, 1.0f, 1.0f)};
    case ShapeKind::cone: {
        const float r = std::max(1.0f, object.top_radius);
        return {Vec3(-r, 0.0f, -r), Vec3(r, 1.0f, r)};
    }
    case ShapeKind::triangle:
    case ShapeKind::mesh:
        return meshes[object.mesh].bounds;
    case ShapeKind::plane:
        break;
    }
    return {};
}

std::pair<DVec3, DVec3> transformed_box(const Bounds& local, const DMat4& m) {
    DVec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int corner = 0; corner < 8; ++corner) {
        const DVec3 p((corner & 1) ? local.hi.x : local.lo.x,
                      (corner & 2) ? local.hi.y : local.lo.y,
                      (corner & 4) ? local.hi.z : local.lo.z);
        const DVec3 w = DVec3(m * glm::dvec4(p, 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    return {lo, hi};
}

} // namespace glint
