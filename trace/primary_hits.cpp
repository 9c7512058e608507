#include "trace/primary_hits.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>

namespace glint {
inline namespace GLINT_PRECISION {

// The exact-mode argument. The id image comes from surfaces that enclose each object's true
// surface (conservative tessellation), or lie on it up to float rounding (proxies, planes,
// triangles and meshes, whose drawn depth is their true one), so along a pixel's ray every
// object's true hit lies at or beyond its drawn hit, up to that rounding, and the depth test kept
// the nearest drawn hit, at distance t_r. Hence no object's true surface lies before t_r, and the
// named object's true hit t_k ≥ t_r: any other object that is really first must be hit in
// [t_r, t_k]. t_r comes from a float depth buffer (and a proxy's depth from the fragment shader's
// float arithmetic), so the interval starts a relative kDepthSlack earlier: far beyond either
// rounding, and it costs nothing to be generous, since what is found there must still be hit
// before t_k.
//
// Which objects can be hit there is decided without a query through the structure:
//   - the object's bounds, projected onto the image, must cover the pixel's bin (ScreenBins:
//     a ray that meets an object meets its box, whose projection is the hull of its corners'),
//     and a plane must lie in front of the eye somewhere in the bin,
//   - and its range of view depth (a plane's over the bin) must reach the interval's,
//     [t_r·(1 − slack), t_k] in view depth (t times the direction's forward component).
// With exact depths (proxies, planes, flat triangles) the interval is only rounding wide, and
// nearly every pixel has no object left to test; a tessellation widens it by its deviation. Each
// object left is intersected exactly, with the tracer's own routine; only when one is hit before
// t_k (or at t_k with a lower index: the tracer's tie rule) is the pixel traced in full from the
// eye, so the hit is exactly ray mode's.
//
// Coverage is conservative only up to rounding: at a pixel centre within rounding of a
// silhouette edge (a box face, a triangle, a proxy fragment's own intersection), GL and the
// tracer may disagree on whether the edge's object covers it, and the id image may then name
// the object behind. Such pixels lie where ids change, so on an id boundary (a neighbour of the
// 8 carries another id) the interval starts at the eye: every object of the bin that may lie
// in front of t_k is tested. So does a pixel where nothing was drawn: an object thinner than a
// pixel can be missed at a pixel centre by a proxy's float intersection (SPD's tree-11, whose
// branches are cylinders under a pixel wide: 3 pixels of 262,144) with no id change around it
// to say so; the bins keep this cheap where no object's projection reaches.
//
// Cut-outs (DESIGN §13) break the first step: the id pass discards a fragment where GL's
// texture lookup finds the alpha below the cut-off, and GL's filtering is not the tracer's to the
// bit, so at a mask's edge a surface the tracer keeps may be missing from the depth buffer, in
// front of t_r. An object whose material cuts out is therefore tested from the eye at every
// pixel its bin entry covers. The other direction needs nothing: a fragment GL keeps and the
// tracer cuts away only makes t_r nearer, and a named object the tracer passes through is hit
// farther on (or not at all: a fallback).
constexpr Real kDepthSlack = 1e-3_r;

// How much wider than their corners' the objects' depth ranges are kept: the pixel's view depth
// is t times a cosine, both in float, so relative rounding of a few ulps; this is 1,000× that.
constexpr double kDepthRangeSlack = 1e-4;

namespace {

bool on_id_boundary(const IdImage& ids, int x, int y) {
    const int w = ids.width;
    const std::uint32_t* row = &ids.ids[static_cast<std::size_t>(y) * w + x];
    const std::uint32_t own = *row;
    if (x > 0 && x + 1 < w && y > 0 && y + 1 < ids.height) { // every pixel but the border's
        const std::uint32_t *up = row - w, *down = row + w;
        return ((up[-1] ^ own) | (up[0] ^ own) | (up[1] ^ own) | (row[-1] ^ own) | (row[1] ^ own) |
                (down[-1] ^ own) | (down[0] ^ own) | (down[1] ^ own)) != 0;
    }
    return any_in_neighbourhood(ids.width, ids.height, x, y, [&](int nx, int ny) {
        return ids.ids[static_cast<std::size_t>(ny) * w + nx] != own;
    });
}

// Whether every pixel of [x0, x1) × [y0, y1) names `id`.
bool one_object(const IdImage& ids, int x0, int y0, int x1, int y1, std::uint32_t id) {
    for (int y = y0; y < y1; ++y) {
        const std::uint32_t* row = &ids.ids[static_cast<std::size_t>(y) * ids.width];
        for (int x = x0; x < x1; ++x)
            if (row[x] != id) return false;
    }
    return true;
}

} // namespace

namespace {

// A plane's range of view depth over the pixels [x0, x1] × [y0, y1] of a width × height image,
// or nothing where its rays meet it only behind the eye. The tracer meets the plane y = 0 of
// object space at t = c / (n·d), n = the second row of M⁻¹ and c = −(M⁻¹'s offset).y (rays
// start at the eye, the origin); with d ∝ v = forward + X·right + Y·up, whose forward component
// is 1, the view depth is c / (n·v), and n·v is linear in the pixel, so its extremes over the
// rectangle are at the corner pixels' centres. n·v is widened by 10⁻⁵ of |n|·|v|, orders beyond
// the float rounding of the tracer's n·d; an interval that then reaches 0 (the horizon) is
// unbounded.
std::optional<std::pair<double, double>> plane_depths(const PinholeCamera& camera,
                                                      const Transform& m, int width, int height,
                                                      int x0, int y0, int x1, int y1) {
    const Mat3& l = m.inverse_linear;
    const DVec3 n(l[0][1], l[1][1], l[2][1]);
    const double c = -static_cast<double>(m.inverse_offset.y);
    const DVec3 f(camera.forward()), r(camera.right_scaled()), u(camera.up_scaled());
    double lo = kInfinity, hi = -kInfinity;
    for (const int px : {x0, x1})
        for (const int py : {y0, y1}) {
            const double x = 2 * (px + 0.5) / width - 1, y = 1 - 2 * (py + 0.5) / height;
            const double nv = glm::dot(n, f + x * r + y * u);
            lo = std::min(lo, nv), hi = std::max(hi, nv);
        }
    const double slack = 1e-5 * glm::length(n) * (1 + glm::length(r) + glm::length(u));
    lo -= slack, hi += slack;
    if (c == 0 || (lo <= 0 && hi >= 0)) return std::pair{-double(kInfinity), double(kInfinity)};
    const double z0 = c / lo, z1 = c / hi;
    if (z0 < 0) return std::nullopt; // both of one sign: behind the eye
    return std::pair{std::min(z0, z1), std::max(z0, z1)};
}

} // namespace

void bin_objects(const World& world, IdImage& ids) {
    ScreenBins& bins = ids.bins;
    constexpr int k = ScreenBins::kSize;
    bins.columns = (ids.width + k - 1) / k, bins.rows = (ids.height + k - 1) / k;
    const PinholeCamera& camera = world.camera();
    const std::vector<Object>& objects = world.objects();
    const auto count = static_cast<std::uint32_t>(objects.size());
    const PixelRect image{0, 0, ids.width - 1, ids.height - 1};
    const auto widened = [](std::uint32_t object, double near, double far, PixelRect pixels) {
        return ScreenBins::Entry{object,
                                 static_cast<Real>(near - kDepthRangeSlack * std::abs(near)),
                                 static_cast<Real>(far + kDepthRangeSlack * std::abs(far)), pixels};
    };
    // Bounded objects: one range each, and their rectangles' bins, or every bin when they reach
    // behind the eye.
    bins.everywhere.clear();
    std::vector<std::optional<PixelRect>> rects(count);
    std::vector<ScreenBins::Entry> ranges(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        if (!objects[i].bounded) continue;
        const ProjectedBounds seen =
            project_bounds(camera, objects[i].bounds, ids.width, ids.height);
        rects[i] = seen.pixels;
        ranges[i] = widened(i, seen.near, seen.far, rects[i].value_or(image));
        if (!rects[i]) bins.everywhere.push_back(ranges[i]);
    }
    // Every entry of object i: body(bin, entry). A plane has a range per bin (plane_depths, over
    // the bin's pixels and one more on each side) and no entry where it lies behind the eye.
    const auto for_each_entry = [&](std::uint32_t i, auto&& body) {
        if (!objects[i].bounded) {
            for (int by = 0; by < bins.rows; ++by)
                for (int bx = 0; bx < bins.columns; ++bx)
                    if (const auto z =
                            plane_depths(camera, objects[i].transform, ids.width, ids.height,
                                         bx * k - 1, by * k - 1, std::min(bx * k + k, ids.width),
                                         std::min(by * k + k, ids.height)))
                        body(static_cast<std::size_t>(by) * bins.columns + bx,
                             widened(i, z->first, z->second, image));
            return;
        }
        if (!rects[i]) return;
        const PixelRect& r = *rects[i]; // clamped to the image; one wholly off it has no bin
        const int x0 = std::max(r.x0, 0), x1 = std::min(r.x1, ids.width - 1);
        const int y0 = std::max(r.y0, 0), y1 = std::min(r.y1, ids.height - 1);
        if (x0 > x1 || y0 > y1) return;
        for (int by = y0 / k; by <= y1 / k; ++by)
            for (int bx = x0 / k; bx <= x1 / k; ++bx)
                body(static_cast<std::size_t>(by) * bins.columns + bx, ranges[i]);
    };
    // Two passes: count per bin, then fill, objects in index order.
    std::vector<std::uint32_t> per_bin(static_cast<std::size_t>(bins.columns) * bins.rows + 1, 0);
    for (std::uint32_t i = 0; i < count; ++i)
        for_each_entry(i, [&](std::size_t bin, const ScreenBins::Entry&) { ++per_bin[bin + 1]; });
    for (std::size_t b = 1; b < per_bin.size(); ++b) per_bin[b] += per_bin[b - 1];
    bins.first = per_bin;
    bins.entries.resize(per_bin.back());
    for (std::uint32_t i = 0; i < count; ++i)
        for_each_entry(i, [&](std::size_t bin, const ScreenBins::Entry& entry) {
            bins.entries[per_bin[bin]++] = entry;
        });
}

namespace {

// resolve_pixel, with the camera ray made by make_ray() only where it is needed: a pixel where
// nothing was drawn needs none under trust, nor under exact where no object is binned.
// `named`, where given, is the ray's hit on the object the pixel names (intersect_one's answer,
// found with its block's packet).
template <class MakeRay>
Hit resolve_with(const World& world, const IdImage& ids, Resolve resolve, int x, int y,
                 const MakeRay& make_ray, PrimaryStats& stats, const Hit* named = nullptr) {
    const std::size_t p = static_cast<std::size_t>(y) * ids.width + x;
    const bool exact = resolve == Resolve::exact;
    const bool edge = exact && on_id_boundary(ids, x, y);
    if (edge) ++stats.edges;
    const std::uint32_t id = ids.ids[p];
    if (id == 0 && !exact) return {}; // nothing drawn: trust says nothing is there
    const ScreenBins& bins = ids.bins;
    const std::size_t bin = static_cast<std::size_t>(y / ScreenBins::kSize) * bins.columns +
                            static_cast<std::size_t>(x / ScreenBins::kSize);
    const bool binned = !bins.empty();
    // Nothing drawn, and no object's projection reaches the pixel: nothing is there to test.
    if (id == 0 && binned && bins.everywhere.empty() && bins.first[bin] == bins.first[bin + 1])
        return {};
    const Ray ray = make_ray();
    const auto trace = [&] {
        ++stats.traced;
        return world.intersect(ray);
    };
    const std::uint32_t object = id - 1; // kNoObject for the background
    Hit hit;
    if (id != 0) {
        ++stats.exact_intersections;
        hit = named ? *named : world.intersect_one(object, ray);
        if (!hit.found()) { // inside the enclosing surface but outside the true one
            ++stats.fallbacks;
            return trace();
        }
    }
    if (!exact) return hit;
    if (!binned) return trace();
    const Real cosine = glm::dot(ray.direction, world.camera().forward());
    const Real z_hit = hit.found() ? hit.t * cosine : kInfinity;
    const Real z_from = edge || id == 0 ? -kInfinity : ids.view_depth[p] * (1 - kDepthSlack);
    const Real limit = hit.found() ? std::nextafter(hit.t, kInfinity) : kInfinity;
    bool tested = false;
    const auto in_front = [&](const ScreenBins::Entry& other) {
        if (other.object == object || other.near > z_hit || !other.covers(x, y)) return false;
        if (other.far < z_from && !world.objects()[other.object].params.cut_out) return false;
        tested = true;
        ++stats.tests;
        const Hit h = world.intersect_one(other.object, ray, limit);
        return h.found() && (h.t < hit.t || (h.t == hit.t && other.object < object));
    };
    bool found = false;
    for (const ScreenBins::Entry& other : bins.everywhere)
        if ((found = in_front(other))) break;
    for (std::uint32_t e = bins.first[bin]; !found && e < bins.first[bin + 1]; ++e)
        found = in_front(bins.entries[e]);
    if (tested) ++stats.checked;
    if (!found) return hit;
    const Hit nearer = trace();
    if (nearer.object != hit.object) ++stats.corrected;
    return nearer;
}

} // namespace

Hit resolve_pixel(const World& world, const IdImage& ids, Resolve resolve, int x, int y,
                  const Ray& ray, PrimaryStats& stats) {
    return resolve_with(
        world, ids, resolve, x, y, [&] { return ray; }, stats);
}

void tile_primary_hits(const World& world, const PrimarySource& source, const TileRect& r,
                       Hit* hits, std::size_t stride, PrimaryStats& stats, Ray* rays) {
    const PinholeCamera& camera = world.camera();
    // Pixel (x, y)'s place in `hits`.
    const auto at = [&](int x, int y) {
        return static_cast<std::size_t>(y - r.y0) * stride + static_cast<std::size_t>(x - r.x0);
    };
    static_assert(kBlockSize * kBlockSize == kMaxPacket);
    if (!source.ids) { // ray mode: the tile's camera rays in packets of a block each
        for (int by = r.y0; by < r.y1; by += kBlockSize) {
            for (int bx = r.x0; bx < r.x1; bx += kBlockSize) {
                Ray packet[kMaxPacket];
                Hit block[kMaxPacket];
                std::size_t pixel[kMaxPacket], count = 0;
                for_each_in_blocks(bx, by, std::min(bx + kBlockSize, r.x1),
                                   std::min(by + kBlockSize, r.y1), [&](int x, int y) {
                                       pixel[count] = at(x, y);
                                       packet[count++] = camera.ray(x, y);
                                   });
                world.intersect_packet({packet, count}, block);
                for (std::size_t k = 0; k < count; ++k) hits[pixel[k]] = block[k];
                if (rays)
                    for (std::size_t k = 0; k < count; ++k) rays[pixel[k]] = packet[k];
            }
        }
        return;
    }
    // Hybrid: block by block. A whole block whose pixels all name one object is intersected
    // with it as one packet (World::intersect_one_packet), each pixel's check then as alone.
    const IdImage& ids = *source.ids;
    for (int by = r.y0; by < r.y1; by += kBlockSize) {
        for (int bx = r.x0; bx < r.x1; bx += kBlockSize) {
            const int x1 = std::min(bx + kBlockSize, r.x1), y1 = std::min(by + kBlockSize, r.y1);
            const auto pixel = [&](int x, int y) {
                const auto make_ray = [&] { return camera.ray(x, y); };
                if (!rays) {
                    hits[at(x, y)] =
                        resolve_with(world, ids, source.resolve, x, y, make_ray, stats);
                    return;
                }
                const Ray& ray = rays[at(x, y)] = make_ray();
                hits[at(x, y)] = resolve_with(
                    world, ids, source.resolve, x, y, [&] { return ray; }, stats);
            };
            const std::uint32_t id = ids.ids[static_cast<std::size_t>(by) * ids.width + bx];
            if (id == 0 || !one_object(ids, bx, by, x1, y1, id)) {
                for_each_in_blocks(bx, by, x1, y1, pixel);
                continue;
            }
            Ray packet[kMaxPacket];
            Hit named[kMaxPacket];
            std::size_t count = 0;
            for_each_in_blocks(bx, by, x1, y1,
                               [&](int x, int y) { packet[count++] = camera.ray(x, y); });
            world.intersect_one_packet(id - 1, {packet, count}, named);
            count = 0;
            for_each_in_blocks(bx, by, x1, y1, [&](int x, int y) {
                const std::size_t k = count++;
                hits[at(x, y)] = resolve_with(
                    world, ids, source.resolve, x, y, [&] { return packet[k]; }, stats, &named[k]);
                if (rays) rays[at(x, y)] = packet[k];
            });
        }
    }
}

std::vector<Hit> primary_hits(const World& world, const PrimarySource& source, PrimaryStats& stats,
                              const TileProgress& progress) {
    const PinholeCamera& camera = world.camera();
    std::vector<Hit> hits(static_cast<std::size_t>(camera.width()) * camera.height());
    std::mutex stats_mutex;
    for_each_tile(camera.width(), camera.height(), progress, [&](int x0, int y0, int x1, int y1) {
        PrimaryStats local;
        tile_primary_hits(world, source, {x0, y0, x1, y1},
                          &hits[static_cast<std::size_t>(y0) * camera.width() + x0],
                          static_cast<std::size_t>(camera.width()), local);
        const std::lock_guard lock(stats_mutex);
        stats += local;
    });
    return hits;
}

} // namespace GLINT_PRECISION
} // namespace glint
