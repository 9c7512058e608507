#include "trace/pixel.h"

#include "trace/recorder.h"

namespace glint {
inline namespace GLINT_PRECISION {

PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary,
                        const CastAhead& ahead, RayRecorder* recorder) {
    PixelSample sample;
    sample.hit = primary;
    sample.recorder = recorder;
    ++sample.rays.primary;
    if (recorder) recorder->begin(RayKind::primary, ray, primary, 1, 1, 0);
    if (!primary.found()) {
        sample.note(0);
        sample.colour = world.missed(ray);
    } else {
        const SurfacePoint surface =
            ahead.surfaces ? ahead.surfaces[ahead.node] : world.surface(ray, primary);
        sample.normal = surface.shading;
        sample.colour = shade(world, ray, primary, surface, 0, 1, sample, ahead);
    }
    if (recorder) recorder->end(sample.colour);
    sample.recorder = nullptr; // the sample outlives the call; the recorder need not
    return sample;
}

void TileLighting::prepare(const World& world, std::span<const Ray> rays, std::span<const Hit> hits,
                           int levels) {
    surfaces_.resize(hits.size()); // read only where a hit is found: left as they were
    for (std::size_t k = 0; k < hits.size(); ++k)
        if (hits[k].found()) surfaces_[k] = world.surface(rays[k], hits[k]);
    cast_shadows(world, hits);
    nodes_.clear();
    if (levels == 0) return; // the default path: no node to keep
    for (std::size_t k = 0; k < hits.size(); ++k) nodes_.push_back({rays[k], hits[k], 1});
    std::size_t begin = 0, end = nodes_.size();
    for (int depth = 0; depth < levels && begin < end; ++depth) {
        cast_secondary(world, begin, end, depth);
        begin = end, end = nodes_.size();
    }
}

std::uint32_t TileLighting::add(const World& world, const Ray& ray, const Hit& hit, Real weight) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({ray, hit, weight});
    surfaces_.resize(nodes_.size());
    if (hit.found()) surfaces_.back() = world.surface(ray, hit);
    return index;
}

// At depth d with path weight w, shade() casts a surface's reflected ray, then its transmitted
// one, where casts_secondary(d, w · factor) allows; it may yet find the tree's budget spent.
// The rays go in packets in their sources' order, so that neighbours share packets.
void TileLighting::cast_secondary(const World& world, std::size_t begin, std::size_t end,
                                  int depth) {
    const RenderSettings& settings = world.settings();
    const RayCounts none; // the tree budget: known only to shade()
    next_rays_.clear(), next_skips_.clear(), next_from_.clear();
    const auto gather = [&](const SecondaryRay& next, std::size_t from, int kind, Real weight) {
        next_rays_.push_back(next.ray);
        next_skips_.push_back(next.skip);
        next_from_.push_back({static_cast<std::uint32_t>(from), kind, weight});
    };
    for (std::size_t n = begin; n < end; ++n) {
        const AheadNode& node = nodes_[n];
        if (!node.hit.found()) continue;
        const Phong& m = world.material(node.hit.object);
        const Real reflectivity = reflectivity_at(world, node.hit);
        const Real reflected = node.weight * reflectivity;
        if (reflectivity > 0 && casts_secondary(settings, depth, reflected, none))
            gather(reflected_ray(node.ray, surfaces_[n]), n, 0, reflected);
        const Real transmitted = node.weight * m.transmission;
        if (m.transmission > 0 && casts_secondary(settings, depth, transmitted, none))
            gather(transmitted_ray(node.ray, surfaces_[n], m.ior), n, 1, transmitted);
    }
    Hit found[kMaxPacket];
    for (std::size_t first = 0, count = 0; first < next_rays_.size(); first += count) {
        count = std::min<std::size_t>(kMaxPacket, next_rays_.size() - first);
        world.intersect_packet({&next_rays_[first], count}, found, &next_skips_[first]);
        for (std::size_t r = 0; r < count; ++r) {
            const From& from = next_from_[first + r];
            const std::uint32_t node = add(world, next_rays_[first + r], found[r], from.weight);
            nodes_[from.node].next[from.kind] = node;
        }
    }
}

void TileLighting::cast_shadows(const World& world, std::span<const Hit> hits) {
    const std::size_t lit = hits.size();
    lit_ = lit;
    lights_ = world.lights().size();
    if (lights_ == 0) return;
    light_.assign(lit * lights_, 0);
    const bool glass = world.geometry()->transmissive;
    const bool unlit = world.geometry()->unlit; // most scenes have no unlit material to look up
    for (std::size_t j = 0; j < lights_; ++j) {
        const Light& light = world.lights()[j];
        Ray shadow[kMaxPacket];
        std::uint32_t skip[kMaxPacket];
        std::size_t from[kMaxPacket];
        bool blocked[kMaxPacket], crossed[kMaxPacket] = {};
        std::size_t count = 0;
        const auto cast = [&] {
            if (glass)
                world.opaque_between_packet({shadow, count}, 1.0_r, skip, blocked, crossed);
            else
                world.occluded_packet({shadow, count}, 1.0_r, skip, blocked);
            for (std::size_t r = 0; r < count; ++r)
                light_[from[r] * lights_ + j] = blocked[r]   ? 0.0_r
                                                : crossed[r] ? kThroughGlass
                                                             : 1.0_r;
            count = 0;
        };
        for (std::size_t n = 0; n < lit; ++n) {
            const SurfacePoint& surface = surfaces_[n];
            // An unlit surface casts none (shade() adds no light to it).
            if (!hits[n].found() || (unlit && world.material(hits[n].object).unlit) ||
                !light_direction(surface, light).in_front())
                continue;
            shadow[count] = shadow_ray(surface, light.position);
            skip[count] = surface.skip;
            from[count++] = n;
            if (count == kMaxPacket) cast();
        }
        if (count > 0) cast();
    }
}

} // namespace GLINT_PRECISION
} // namespace glint
