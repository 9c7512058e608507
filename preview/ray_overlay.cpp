#include "preview/ray_overlay.h"

#include <optional>

namespace glint {
namespace {

// Where a camera-relative point lands in the image, for points at least `near` in front of the
// eye: the inverse of PinholeCamera::sample_ray (a point s·(f + x·R + y·U) has view depth s and
// screen position (x, y) ∈ [−1, 1]²).
struct Projection {
    const PinholeCamera& camera;
    static constexpr Real kNear = 1e-4_r;

    Real depth(Vec3 p) const { return glm::dot(p, camera.forward()); }
    std::pair<float, float> pixel(Vec3 p) const {
        const Real z = depth(p);
        const Vec3 r = camera.right_scaled(), u = camera.up_scaled();
        const Real x = glm::dot(p, r) / (glm::dot(r, r) * z);
        const Real y = glm::dot(p, u) / (glm::dot(u, u) * z);
        return {static_cast<float>((x + 1) / 2 * static_cast<Real>(camera.width())),
                static_cast<float>((1 - y) / 2 * static_cast<Real>(camera.height()))};
    }
    // The segment a → b, its part behind the near plane cut away; nothing if all of it is.
    std::optional<OverlaySegment> segment(OverlaySegment::Kind kind, Vec3 a, Vec3 b) const {
        const Real za = depth(a), zb = depth(b);
        if (za < kNear && zb < kNear) return std::nullopt;
        if (za < kNear) a = a + (b - a) * ((kNear - za) / (zb - za));
        if (zb < kNear) b = b + (a - b) * ((kNear - zb) / (za - zb));
        const auto [x0, y0] = pixel(a);
        const auto [x1, y1] = pixel(b);
        return OverlaySegment{kind, x0, y0, x1, y1};
    }
};

} // namespace

std::vector<OverlaySegment> tree_segments(const World& world, const PixelExplanation& e) {
    using Kind = OverlaySegment::Kind;
    const Projection projection{world.camera()};
    std::vector<OverlaySegment> segments;
    const auto add = [&](Kind kind, Vec3 a, Vec3 b) {
        if (const auto s = projection.segment(kind, a, b)) segments.push_back(*s);
    };
    // How far a missing ray is drawn: well past everything, so that it runs off the image or
    // into its vanishing point.
    Real far = 1;
    for (const Object& o : world.objects())
        if (o.bounded) far = std::max(far, glm::length(o.bounds.hi) + glm::length(o.bounds.lo));
    far *= 4;
    for (std::size_t i = 0; i < e.rays.size(); ++i) {
        const RecordedRay& r = e.rays[i];
        const Vec3 d = glm::normalize(r.ray.direction);
        const Vec3 end =
            r.hit.found() ? r.ray.origin + r.hit.t * r.ray.direction : r.ray.origin + far * d;
        if (r.kind == RayKind::primary) {
            const auto [x, y] = projection.pixel(r.ray.origin + d); // on the ray, 1 in front
            segments.push_back({Kind::primary, x, y, x, y});
        } else {
            add(r.kind == RayKind::reflection ? Kind::reflection : Kind::transmission, r.ray.origin,
                end);
        }
        for (const LightTerm& term : r.lights)
            if (term.in_front())
                add(term.through == 0 ? Kind::blocked_shadow : Kind::shadow, r.surface.position,
                    world.lights()[term.light].position);
    }
    return segments;
}

} // namespace glint
