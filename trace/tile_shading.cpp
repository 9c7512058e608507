#include "trace/tile_shading.h"

namespace glint {
inline namespace GLINT_PRECISION {

RenderResult blank_result(const World& world, int samples, const FrameRequest& request) {
    const int width = world.camera().width(), height = world.camera().height();
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    RenderResult result;
    // Every pixel is written by the frame's passes (or, on MPI ranks, by the exchange).
    if (!request.radiance) {
        result.display_bytes = Image::uninitialised(width, height);
    } else {
        result.radiance = FloatImage::uninitialised(width, height);
        if (samples > 1) result.clamped = FloatImage::uninitialised(width, height);
    }
    if (world.geometry()->secondary) result.omitted_weight.resize(pixels);
    if (request.ids) result.ids.resize(pixels);
    if (request.aovs) result.aovs = PrimaryAovs(pixels);
    return result;
}

TileBuffers& tile_buffers() {
    thread_local TileBuffers buffers;
    return buffers;
}

RayCounts shade_tile(const World& world, const Hit* primary, std::size_t stride, const TileRect& r,
                     RenderResult& result, std::vector<std::uint64_t>* path_keys,
                     CentreObserver* observer, const Ray* camera_rays) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width();
    TileBuffers& buffers = tile_buffers();
    std::vector<std::size_t>& pixels = buffers.pixels;
    std::vector<Ray>& rays = buffers.rays;
    std::vector<Hit>& hits = buffers.hits;
    pixels.clear(), rays.clear(), hits.clear();
    for_each_in_blocks(r.x0, r.y0, r.x1, r.y1, [&](int x, int y) {
        const std::size_t at =
            static_cast<std::size_t>(y - r.y0) * stride + static_cast<std::size_t>(x - r.x0);
        pixels.push_back(static_cast<std::size_t>(y) * width + x);
        rays.push_back(camera_rays ? camera_rays[at] : camera.ray(x, y));
        hits.push_back(primary[at]);
    });
    TileLighting& lighting = buffers.lighting;
    lighting.prepare(world, rays, hits, world.settings().packet_levels);
    RayCounts counts;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const std::size_t i = pixels[k];
        const PixelSample sample = shade_pixel(world, rays[k], hits[k], lighting.at(k));
        result.set_omitted(i, static_cast<float>(sample.omitted_weight));
        if (!result.ids.empty()) result.ids[i] = hits[k].found() ? hits[k].object + 1 : 0;
        if (path_keys) (*path_keys)[i] = sample.path_key;
        store_pixel(result, i, sample.colour, glm::clamp(sample.colour, Vec3(0), Vec3(1)));
        store_aovs(result, i, sample.hit, sample.normal);
        if (observer)
            observer->pixel(static_cast<int>(i % width), static_cast<int>(i / width), rays[k],
                            sample);
        counts += sample.rays;
    }
    return counts;
}

} // namespace GLINT_PRECISION
} // namespace glint
