#include "trace/render.h"

#include <mutex>

namespace glint {

RenderResult shade_image(const World& world, const std::vector<Hit>& primary,
                         const TileProgress& progress) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width();
    RenderResult result{Image(width, camera.height()), {}};
    std::mutex counts_mutex;
    for_each_tile(width, camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        RayCounts counts;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                ++counts.primary;
                const Vec3 c =
                    shade(world, camera.ray(x, y), primary[static_cast<std::size_t>(y) * width + x],
                          0, 1.0f, counts);
                std::uint8_t* p = result.image.pixel(x, y);
                p[0] = to_byte(c.x), p[1] = to_byte(c.y), p[2] = to_byte(c.z);
            }
        }
        const std::lock_guard lock(counts_mutex); // integer sums: order does not matter
        result.rays += counts;
    });
    return result;
}

RenderResult render(const World& world, const TileProgress& progress) {
    return shade_image(world, primary_hits_by_ray(world, progress), progress);
}

} // namespace glint
