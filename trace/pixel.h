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

// Shades a camera ray from its primary hit, from what a tile's packets found of it beforehand
// where given (`ahead`, TileLighting: its node's surface, its shadow verdicts, the hits cast
// ahead in its ray tree); reports the ray tree to `recorder` where given (trace/recorder.h:
// `glint explain`).
PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary,
                        const CastAhead& ahead = {}, RayRecorder* recorder = nullptr);

// The primary hits of a tile (or any group of pixels whose neighbours are close), prepared for
// shading: every surface, and every light's shadow verdict, cast in packets of kMaxPacket rays
// towards that light (World::occluded_packet; in a scene with glass
// World::opaque_between_packet, which leaves only the rays that meet glass and nothing opaque for
// shade() to follow), taken in the order given. Then the first `levels` levels of the hits' ray
// trees (RenderSettings::packet_levels), level by level: the reflected and transmitted rays
// shade() casts (casts_secondary), in packets of kMaxPacket rays in their sources' order
// (World::intersect_packet), and their hits' surfaces; their shadow rays shade() casts one at a
// time. Every hit and verdict is the one shade() would find ray by ray, bit for bit; a ray cast
// ahead that shade() does not cast after all (where the tree has spent kMaxTreeRays by then) is
// left unused.
//
// No level by default: on SPD's scenes and on facing flat mirrors one level took 0.97 to 1.03 of
// the frame's time without, and deeper ones lost on glass; shadow packets for the new hits were
// slower too (docs/PERFORMANCE.md, "Round two's last changes, and secondary rays in packets").
class TileLighting {
  public:
    TileLighting() = default;
    TileLighting(const World& world, std::span<const Ray> rays, std::span<const Hit> hits,
                 int levels = 0) {
        prepare(world, rays, hits, levels);
    }
    // Prepares another group in the storage of the last, which it allocates again only to grow.
    void prepare(const World& world, std::span<const Ray> rays, std::span<const Hit> hits,
                 int levels = 0);
    // Pixel k's (the k-th hit given).
    CastAhead at(std::size_t k) const {
        return {surfaces_.data(), nodes_.empty() ? nullptr : nodes_.data(),
                lights_ > 0 ? light_.data() : nullptr, static_cast<std::uint32_t>(k),
                static_cast<std::uint32_t>(lit_)};
    }

  private:
    // Casts the shadow rays of the primary hits.
    void cast_shadows(const World& world, std::span<const Hit> hits);
    // Adds a node for `hit`, found by `ray` on a path of weight `weight`; returns its index.
    std::uint32_t add(const World& world, const Ray& ray, const Hit& hit, Real weight);
    // Casts the reflected and transmitted rays of nodes [begin, end), at `depth`; their hits
    // become the nodes from `end` on.
    void cast_secondary(const World& world, std::size_t begin, std::size_t end, int depth);

    // Pixel k's primary hit is node k, then come the levels cast ahead.
    std::vector<SurfacePoint> surfaces_; // node n's (read only where its hit is found)
    std::vector<AheadNode> nodes_;       // empty where no level is cast ahead
    std::vector<Real> light_;            // node n, light j at n·lights + j (1, 0 or kThroughGlass)
    std::size_t lights_ = 0;
    std::size_t lit_ = 0; // the nodes with verdicts: the primary hits
    // A level's rays to cast, and where each comes from: the node it leaves, whether it is that
    // node's reflected (0) or transmitted (1) ray (AheadNode::next), and the path weight.
    struct From {
        std::uint32_t node;
        int kind;
        Real weight;
    };
    std::vector<Ray> next_rays_;
    std::vector<std::uint32_t> next_skips_;
    std::vector<From> next_from_;
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
