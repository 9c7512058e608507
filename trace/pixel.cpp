#include "trace/pixel.h"

namespace glint {
inline namespace GLINT_PRECISION {

PixelSample shade_pixel(const World& world, const Ray& ray, const Hit& primary) {
    PixelSample sample;
    sample.hit = primary;
    ++sample.rays.primary;
    if (!primary.found()) {
        sample.note(0);
        sample.colour = world.background();
        return sample;
    }
    const SurfacePoint surface = world.surface(ray, primary);
    sample.normal = surface.shading;
    sample.colour = shade(world, ray, primary, surface, 0, 1, sample);
    return sample;
}

} // namespace GLINT_PRECISION
} // namespace glint
