#include "trace/pixel.h"

#include "trace/recorder.h"

namespace glint {
inline namespace GLINT_PRECISION {

PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary,
                        const PreparedHit& prepared, RayRecorder* recorder) {
    PixelSample sample;
    sample.hit = primary;
    sample.recorder = recorder;
    ++sample.rays.primary;
    if (recorder) recorder->begin(RayKind::primary, ray, primary, 1, 1, 0);
    if (!primary.found()) {
        sample.note(0);
        sample.colour = world.background();
    } else {
        const SurfacePoint surface =
            prepared.surface ? *prepared.surface : world.surface(ray, primary);
        sample.normal = surface.shading;
        sample.colour = shade(world, ray, primary, surface, 0, 1, sample, prepared.light);
    }
    if (recorder) recorder->end(sample.colour);
    sample.recorder = nullptr; // the sample outlives the call; the recorder need not
    return sample;
}

void TileLighting::prepare(const World& world, std::span<const Ray> rays,
                           std::span<const Hit> hits) {
    surfaces_.resize(hits.size()); // read only where a hit is found: left as they were
    lights_ = world.lights().size();
    known_ = lights_ > 0;
    for (std::size_t k = 0; k < hits.size(); ++k)
        if (hits[k].found()) surfaces_[k] = world.surface(rays[k], hits[k]);
    if (!known_) return;
    light_.assign(hits.size() * lights_, 0);
    const bool glass = world.geometry()->transmissive;
    for (std::size_t j = 0; j < lights_; ++j) {
        const Light& light = world.lights()[j];
        Ray shadow[kMaxPacket];
        std::uint32_t skip[kMaxPacket];
        std::size_t pixel[kMaxPacket];
        bool blocked[kMaxPacket], crossed[kMaxPacket] = {};
        std::size_t count = 0;
        const auto cast = [&] {
            if (glass)
                world.opaque_between_packet({shadow, count}, 1.0_r, skip, blocked, crossed);
            else
                world.occluded_packet({shadow, count}, 1.0_r, skip, blocked);
            for (std::size_t r = 0; r < count; ++r)
                light_[pixel[r] * lights_ + j] = blocked[r]   ? 0.0_r
                                                 : crossed[r] ? kThroughGlass
                                                              : 1.0_r;
            count = 0;
        };
        for (std::size_t k = 0; k < hits.size(); ++k) {
            if (!hits[k].found() || !light_direction(surfaces_[k], light).in_front()) continue;
            shadow[count] = shadow_ray(surfaces_[k], light.position);
            skip[count] = surfaces_[k].skip;
            pixel[count++] = k;
            if (count == kMaxPacket) cast();
        }
        if (count > 0) cast();
    }
}

} // namespace GLINT_PRECISION
} // namespace glint
