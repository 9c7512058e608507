#include "trace/sampling.h"

#include "trace/render.h"
#include "trace/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mutex>

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

// The bytes of the pixels marked in `which`, from `colour` into `bytes`.
void copy_bytes(const FloatImage& colour, const std::vector<std::uint8_t>& which, Image& bytes) {
    for (std::size_t i = 0; i < which.size(); ++i)
        if (which[i])
            for (int c = 0; c < 3; ++c) bytes.rgb[3 * i + c] = to_byte(colour.rgb[3 * i + c]);
}

// The primary hits of the tile's pixel centres (§2's ray, whatever the grid) into result.aovs:
// from the centres' item buffer where the source has one, else by camera ray. Returns the rays.
RayCounts centre_aovs(const World& world, const PrimarySource& source, int x0, int y0, int x1,
                      int y1, RenderResult& result) {
    const PinholeCamera& camera = world.camera();
    const PrimarySource centres{source.ids, source.resolve};
    PrimaryStats unused; // the AOVs' own rays: not the frame's resolve figures
    RayCounts counts;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const Ray ray = camera.ray(x, y);
            const Hit hit = primary_hit(world, centres, x, y, ray, unused);
            const Vec3 normal = hit.found() ? world.surface(ray, hit).shading : Vec3(0);
            store_aovs(result, static_cast<std::size_t>(y) * camera.width() + x, hit, normal);
            ++counts.primary;
        }
    }
    return counts;
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

GridPixel trace_grid(const World& world, const PrimarySource& source, int x, int y,
                     std::vector<Hit>& hits, PrimaryStats& stats) {
    const auto n = static_cast<std::size_t>(world.settings().samples);
    hits.resize(n * n);
    grid_hits(world, source, x, y, hits.data(), stats);
    return shade_grid(world, x, y, hits.data());
}

void supersample(const World& world, const PrimarySource& source,
                 const std::vector<std::uint8_t>* only, RenderResult& result, PrimaryStats& stats,
                 const TileProgress& progress, PhaseTimes& times) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width(), n = world.settings().samples;
    const std::size_t grid = static_cast<std::size_t>(n) * n;
    std::mutex mutex;
    double primary_seconds = 0, shading_seconds = 0; // summed over tiles, all threads
    const Stopwatch wall;
    for_each_tile(width, camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        Stopwatch watch;
        PrimaryStats local_stats;
        std::vector<std::size_t> pixels; // the tile's pixels to sample, in row order
        std::vector<Hit> hits;           // their grids' primary hits, one grid after another
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * width + x;
                if (only && !(*only)[i]) continue;
                pixels.push_back(i);
                hits.resize(hits.size() + grid);
                grid_hits(world, source, x, y, &hits[hits.size() - grid], local_stats);
            }
        }
        RayCounts counts;
        if (!only && !result.aovs.empty()) counts += centre_aovs(world, source, x0, y0, x1, y1, result);
        const double primary = watch.lap();
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            const std::size_t i = pixels[k];
            const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
            const GridPixel pixel = shade_grid(world, x, y, &hits[k * grid]);
            store_pixel(result, i, pixel.radiance, pixel.mean);
            result.omitted_weight[i] = static_cast<float>(pixel.omitted_weight);
            if (!only) result.ids[i] = pixel.centre_id;
            counts += pixel.rays;
        }
        const double shading = watch.lap();
        const std::lock_guard lock(mutex); // integer sums: order does not matter
        result.rays += counts;
        stats += local_stats;
        primary_seconds += primary, shading_seconds += shading;
        if (progress.tiles_done) progress.tiles_done->fetch_add(1, std::memory_order_relaxed);
    });
    times.add_split(wall.seconds(), primary_seconds, shading_seconds);
}

void render_uniform_grids(const World& world, const PrimarySource& source, PrimaryStats& stats,
                          const TileProgress& progress, PhaseTimes& times, RenderResult& result) {
    supersample(world, source, nullptr, result, stats, progress, times);
}

void refine_adaptively(const World& world, const PrimarySource& source,
                       const std::vector<std::uint64_t>& path_keys, RenderResult& result,
                       PrimaryStats& stats, const TileProgress& progress, PhaseTimes& times) {
    const RenderSettings& settings = world.settings();
    // The rule reads the display's bytes (DESIGN §11): the first pass's, and after each pass
    // those of the pixels it refined.
    const Image first = result.bytes();
    result.refined = timed(times.shading, [&] {
        return adaptive_refinement(first, path_keys, source.sample_ids, settings.samples,
                                   settings.aa_threshold);
    });
    supersample(world, source, &result.refined, result, stats, progress, times);
    if (progress.exchange) progress.exchange->share(result, nullptr);
    // The rounds' scans count as shading; supersample times its own passes.
    const double timed_before = times.primary + times.shading;
    const Stopwatch rounds;
    Image current = first;
    copy_bytes(result.display(), result.refined, current);
    spread_refinement(first, current, result.refined, settings.aa_threshold,
                      [&](const std::vector<std::uint8_t>& next) {
                          supersample(world, source, &next, result, stats,
                                      {progress.threads, nullptr, progress.exchange}, times);
                          if (progress.exchange) progress.exchange->share(result, nullptr);
                          copy_bytes(result.display(), next, current);
                          return true;
                      });
    times.shading += rounds.seconds() - (times.primary + times.shading - timed_before);
}

} // namespace GLINT_PRECISION
} // namespace glint
