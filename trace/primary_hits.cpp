#include "trace/primary_hits.h"

#include <mutex>

namespace glint {
inline namespace GLINT_PRECISION {

// The exact-mode argument. The id image comes from surfaces that enclose each object's true
// surface (conservative tessellation, or exact proxies), so along a pixel's ray every object's
// true hit lies at or beyond its rasterized hit, and the depth test kept the nearest rasterized
// hit, at distance t_r. Hence no object's true surface lies before t_r, and the named object's
// true hit t_k ≥ t_r. Any other object that is really first must therefore be hit in [t_r, t_k):
// one any-hit query over that interval (excluding the named object) decides, and only when it
// finds something is the pixel traced in full. t_r comes from a float depth buffer, so the
// interval starts a relative 1e-3 earlier: far beyond the depth's rounding, and costing only a
// slightly longer query, since anything found must still lie before t_k.
//
// Coverage is conservative only up to rounding: at a pixel centre within float rounding of a
// silhouette edge (a box face, a triangle, a proxy fragment's own intersection), GL and the
// tracer may disagree on whether the edge's object covers it, and the id image may then name
// the object behind. Such pixels lie where ids change, so exact mode traces every pixel whose
// 8 neighbours do not all carry its id.
constexpr Real kDepthSlack = 1e-3_r;

namespace {

bool on_id_boundary(const IdImage& ids, int x, int y) {
    const auto id = [&](int px, int py) {
        return ids.ids[static_cast<std::size_t>(py) * ids.width + px];
    };
    const std::uint32_t own = id(x, y);
    return any_in_neighbourhood(ids.width, ids.height, x, y,
                                [&](int nx, int ny) { return id(nx, ny) != own; });
}

} // namespace

Hit resolve_pixel(const World& world, const IdImage& ids, Resolve resolve, int x, int y,
                  const Ray& ray, PrimaryStats& stats) {
    const PinholeCamera& camera = world.camera();
    const std::size_t p = static_cast<std::size_t>(y) * ids.width + x;
    if (resolve == Resolve::exact && on_id_boundary(ids, x, y)) {
        ++stats.edges;
        return world.intersect(ray);
    }
    if (ids.ids[p] == 0) return {}; // nothing drawn: enclosing surfaces cover every true one
    const std::uint32_t object = ids.ids[p] - 1;
    ++stats.exact_intersections;
    Hit hit = world.intersect_one(object, ray);
    if (!hit.found()) { // inside the enclosing surface but outside the true one
        ++stats.fallbacks;
        return world.intersect(ray);
    }
    if (resolve == Resolve::exact) {
        const Real t_raster = ids.view_depth[p] / glm::dot(ray.direction, camera.forward());
        const Real t_start = glm::max(0.0_r, t_raster * (1 - kDepthSlack));
        if (t_start < hit.t && world.occluded({ray.origin + t_start * ray.direction, ray.direction},
                                              hit.t - t_start, object)) {
            // Traced in full from the eye, so the hit is exactly ray mode's.
            const Hit nearer = world.intersect(ray, hit.t);
            if (nearer.found()) ++stats.corrected, hit = nearer;
        }
    }
    return hit;
}

std::vector<Hit> primary_hits(const World& world, const PrimarySource& source, PrimaryStats& stats,
                              const TileProgress& progress) {
    const PinholeCamera& camera = world.camera();
    const int width = camera.width();
    std::vector<Hit> hits(static_cast<std::size_t>(width) * camera.height());
    std::mutex stats_mutex;
    static_assert(kBlockSize * kBlockSize == kMaxPacket);
    for_each_tile(width, camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        PrimaryStats local;
        if (!source.ids) { // ray mode: the tile's camera rays in packets of a block each
            for (int by = y0; by < y1; by += kBlockSize) {
                for (int bx = x0; bx < x1; bx += kBlockSize) {
                    Ray rays[kMaxPacket];
                    Hit block[kMaxPacket];
                    std::size_t pixel[kMaxPacket], count = 0;
                    for_each_in_blocks(bx, by, std::min(bx + kBlockSize, x1),
                                       std::min(by + kBlockSize, y1), [&](int x, int y) {
                                           pixel[count] = static_cast<std::size_t>(y) * width + x;
                                           rays[count++] = camera.ray(x, y);
                                       });
                    world.intersect_packet({rays, count}, block);
                    for (std::size_t r = 0; r < count; ++r) hits[pixel[r]] = block[r];
                }
            }
            return;
        }
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                hits[static_cast<std::size_t>(y) * width + x] =
                    primary_hit(world, source, x, y, camera.ray(x, y), local);
        const std::lock_guard lock(stats_mutex);
        stats += local;
    });
    return hits;
}

} // namespace GLINT_PRECISION
} // namespace glint
