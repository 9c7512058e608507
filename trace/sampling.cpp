#include "trace/sampling.h"


#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace glint {
inline namespace GLINT_PRECISION {

namespace {

bool contrasts(const std::uint8_t* p, const std::uint8_t* q, int limit) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(p[c]) - int(q[c])) > limit) return true;
    return false;
}

// Bytes differ by more than threshold·255 (a threshold of 0 refines any difference at all).
int contrast_limit(float threshold) {
    return static_cast<int>(std::floor(threshold * 255.0f + 1e-4f));
}

// Whether the n×n ids of pixel (x, y) in the sample grid's id image are not all one id.
bool mixed_ids(const IdImage& samples, int x, int y, int n) {
    const std::uint32_t first =
        samples.ids[static_cast<std::size_t>(y) * n * samples.width + std::size_t(x) * n];
    for (int b = 0; b < n; ++b) {
        const std::uint32_t* row =
            &samples
                 .ids[(static_cast<std::size_t>(y) * n + b) * samples.width + std::size_t(x) * n];
        for (int a = 0; a < n; ++a)
            if (row[a] != first) return true;
    }
    return false;
}

} // namespace

std::vector<std::uint8_t> adaptive_refinement(const Image& first,
                                              const std::vector<std::uint64_t>& path_keys,
                                              const IdImage* sample_ids, int n, float threshold) {
    const int width = first.width, height = first.height;
    const int limit = contrast_limit(threshold);
    std::vector<std::uint8_t> refine(static_cast<std::size_t>(width) * height, 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * width + x;
            const bool edge = (sample_ids && mixed_ids(*sample_ids, x, y, n)) ||
                              any_in_neighbourhood(width, height, x, y, [&](int qx, int qy) {
                                  const std::size_t q = static_cast<std::size_t>(qy) * width + qx;
                                  return path_keys[q] != path_keys[p] ||
                                         contrasts(first.pixel(x, y), first.pixel(qx, qy), limit);
                              });
            refine[p] = edge ? 1 : 0;
        }
    }
    return refine;
}

std::vector<std::uint8_t> adaptive_spread(const Image& first, const Image& current,
                                          const std::vector<std::uint8_t>& refined, float threshold,
                                          std::size_t& added) {
    const int width = first.width, height = first.height;
    const int limit = contrast_limit(threshold);
    std::vector<std::uint8_t> next(refined.size(), 0);
    added = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t q = static_cast<std::size_t>(y) * width + x;
            if (!refined[q] || !contrasts(first.pixel(x, y), current.pixel(x, y), limit)) continue;
            any_in_neighbourhood(width, height, x, y, [&](int px, int py) {
                const std::size_t p = static_cast<std::size_t>(py) * width + px;
                if (!refined[p] && !next[p]) next[p] = 1, ++added;
                return false; // every neighbour
            });
        }
    }
    return next;
}

void grid_hits(const World& world, const PrimarySource& source, int x, int y, Hit* hits,
               PrimaryStats& stats) {
    const PinholeCamera& camera = world.camera();
    const int n = world.settings().samples;
    for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
            const Ray ray = camera.sample_ray(x, y, a, b, n);
            *hits++ = source.sample_ids ? resolve_pixel(world, *source.sample_ids, source.resolve,
                                                        x * n + a, y * n + b, ray, stats)
                                        : world.intersect(ray);
        }
    }
}

GridPixel shade_grid(const World& world, int x, int y, const Hit* hits, RayRecorder* recorder,
                     int recorded) {
    const PinholeCamera& camera = world.camera();
    const int n = world.settings().samples;
    const Real inverse_count = 1 / static_cast<Real>(n * n);
    GridPixel pixel;
    Vec3 sum(0), unclamped(0);
    Real omitted = 0;
    for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
            const PixelSample sample = shade_pixel(world, camera.sample_ray(x, y, a, b, n), *hits++,
                                                   {}, b * n + a == recorded ? recorder : nullptr);
            sum += glm::clamp(sample.colour, Vec3(0), Vec3(1));
            unclamped += sample.colour;
            omitted += sample.omitted_weight;
            pixel.rays += sample.rays;
            if (a == n / 2 && b == n / 2)
                pixel.centre_id = sample.hit.found() ? sample.hit.object + 1 : 0;
        }
    }
    pixel.mean = sum * inverse_count;
    pixel.radiance = unclamped * inverse_count;
    pixel.omitted_weight = omitted * inverse_count;
    return pixel;
}

} // namespace GLINT_PRECISION
} // namespace glint
