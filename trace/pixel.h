// One pixel's path, the only one: its primary hit (by camera ray or from the item buffer's ids,
// trace/primary_hits.h), then Whitted shading (trace/shading.h). The headless render, the hybrid
// resolve and the preview's refiner all trace pixels through here; what a view or a report
// shows beside the colour comes from what this path computed, not from a second intersection.
#pragma once

#include "trace/primary_hits.h"
#include "trace/shading.h"

namespace glint {
inline namespace GLINT_PRECISION {

// A pixel's colour and what its path found: the ray tree's tallies (trace/shading.h) and the
// primary hit, from which the preview's views are drawn.
struct PixelSample : RayTree {
    Vec3 colour{0}; // unclamped
    Hit hit;        // the primary hit (maybe none)
    Vec3 normal{0}; // unit shading normal at the primary hit; zero where there is none
};

// What a tile's packets found at a primary hit before it is shaded (TileLighting): its surface,
// and per light the shadow ray's verdict.
struct PreparedHit {
    const SurfacePoint* surface = nullptr;
    const Real* light = nullptr; // null: shade casts its shadow rays itself
};

// Shades a camera ray from its primary hit, from what `prepared` holds of it where given;
// reports the ray tree to `recorder` where given (trace/recorder.h: `glint explain`).
PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary,
                        const PreparedHit& prepared = {}, RayRecorder* recorder = nullptr);

// The primary hits of a tile (or any group of pixels whose neighbours are close), prepared for
// shading: every surface, and every light's shadow verdict, cast in packets of kMaxPacket rays
// towards that light (World::occluded_packet; in a scene with glass
// World::opaque_between_packet, which leaves only the rays that meet glass and nothing opaque for
// shade() to follow), taken in the order given. The verdicts are the ones shade() would find ray
// by ray, bit for bit.
class TileLighting {
  public:
    TileLighting() = default;
    TileLighting(const World& world, std::span<const Ray> rays, std::span<const Hit> hits) {
        prepare(world, rays, hits);
    }
    // Prepares another group in the storage of the last, which it allocates again only to grow.
    void prepare(const World& world, std::span<const Ray> rays, std::span<const Hit> hits);
    PreparedHit at(std::size_t k) const {
        return {&surfaces_[k], known_ ? &light_[k * lights_] : nullptr};
    }

  private:
    std::vector<SurfacePoint> surfaces_;
    std::vector<Real> light_; // pixel k, light j at k·lights + j (1, 0 or kThroughGlass)
    std::size_t lights_ = 0;
    bool known_ = false;
};

// The whole path of pixel (x, y): its camera ray, made once, its primary hit from `source`,
// then shading.
inline PixelSample trace_pixel(const World& world, const PrimarySource& source, int x, int y,
                               PrimaryStats& stats) {
    const Ray ray = world.camera().ray(x, y);
    return shade_pixel(world, ray, primary_hit(world, source, x, y, ray, stats));
}

} // namespace GLINT_PRECISION
} // namespace glint
