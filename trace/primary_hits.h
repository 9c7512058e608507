// Primary visibility (docs/ARCHITECTURE.md, "A frame's journey", step 3): which object each pixel's
// camera ray hits first. Two sources, one result: cast every camera ray, or start from an id image
// rasterized elsewhere (the item buffer) and intersect each pixel's ray exactly with the object it
// names. trace/ only sees the id image; how it was made is raster/'s business.
#pragma once

#include "trace/names.h"
#include "trace/tiles.h"
#include "trace/world.h"

#include <vector>

namespace glint {

// How far to trust the id image: `exact` checks that nothing lies in front of the exact hit on
// the named object within the interval the rasterized surface leaves uncertain; `trust` does not.
enum class Resolve { exact, trust };

template <> struct EnumNames<Resolve> {
    static constexpr auto names = name_table("exact", "trust");
};

inline namespace GLINT_PRECISION {

// Which objects the rays of each 8×8 bin of an id image's pixels may meet, each with its range of
// view depth (distance along the camera's forward axis) there (bin_objects): a bounded object in
// the bins its projected bounds cover, with its bounds' range and pixels; a plane in the bins
// where it lies in front of the eye, with its range over the bin. The exact resolve tests only
// these, and of them only those whose pixels hold the pixel and whose range reaches the
// interval it must check (primary_hits.cpp).
struct ScreenBins {
    static constexpr int kSize = 8; // pixels on a side of a bin
    struct Entry {
        std::uint32_t object;
        Real near, far; // widened
        // The pixels its projected bounds cover (project_bounds: one pixel wider than its
        // corners'); the whole image for a plane and for bounds reaching behind the eye.
        PixelRect pixels;

        bool covers(int x, int y) const {
            return x >= pixels.x0 && x <= pixels.x1 && y >= pixels.y0 && y <= pixels.y1;
        }
    };
    int columns = 0, rows = 0;
    std::vector<std::uint32_t> first; // per bin, its first entry in `entries` (+ one end)
    std::vector<Entry> entries;       // bin by bin, in object order
    std::vector<Entry> everywhere;    // bounded objects reaching behind the eye: every bin

    bool empty() const { return first.empty(); }
};

// Per pixel, row-major, top row first.
struct IdImage {
    int width = 0, height = 0;
    std::vector<std::uint32_t> ids; // object index + 1; 0 where nothing was drawn
    std::vector<float> view_depth;  // distance along the camera's forward axis of what was drawn
    ScreenBins bins;                // bin_objects(); without them exact resolve traces in full
};

// Fills ids.bins for `world`'s objects seen from its camera at the id image's size (the N× grid
// of samples has N× the camera's: pixel X's centre is the ray of X + 0.5, as for the camera).
void bin_objects(const World& world, IdImage& ids);

struct PrimaryStats {
    std::uint64_t exact_intersections = 0; // pixels resolved by intersecting one named object
    std::uint64_t fallbacks = 0; // the named object was missed: the pixel was fully traced
    std::uint64_t corrected = 0; // exact mode found a nearer object than the named one
    std::uint64_t edges = 0;     // exact mode: on an id boundary, so checked against every
                                 // object in its bin that may lie in front
    std::uint64_t checked = 0;   // exact mode: pixels where some other object survived the bins'
                                 // culls and was intersected
    std::uint64_t tests = 0;     // those intersections, all pixels together
    std::uint64_t traced = 0;    // pixels traced in full (fallbacks, and where a test hit)

    PrimaryStats& operator+=(const PrimaryStats& other) {
        exact_intersections += other.exact_intersections, fallbacks += other.fallbacks;
        corrected += other.corrected, edges += other.edges;
        checked += other.checked, tests += other.tests, traced += other.traced;
        return *this;
    }
};

// Where primary hits come from: each pixel's camera ray (no `ids`, ray mode), or the id image
// (same size as the camera's image) resolved as `resolve` says (hybrid mode).
struct PrimarySource {
    const IdImage* ids = nullptr;
    Resolve resolve = Resolve::exact;
    // With N×N samples per pixel (trace/sampling.h): the id image of the sample grid, N·width ×
    // N·height, sample (a, b) of pixel (i, j) at (N·i + a, N·j + b); `ids` is then the pixel
    // centres' (adaptive antialiasing's first pass), or null.
    const IdImage* sample_ids = nullptr;
};

// Resolves pixel (x, y), whose camera ray is `ray`, from `ids`, counting into `stats`.
Hit resolve_pixel(const World& world, const IdImage& ids, Resolve resolve, int x, int y,
                  const Ray& ray, PrimaryStats& stats);

// Pixel (x, y)'s primary hit from `source`, `ray` its camera ray (stats are counted only when
// resolving ids).
inline Hit primary_hit(const World& world, const PrimarySource& source, int x, int y,
                       const Ray& ray, PrimaryStats& stats) {
    return source.ids ? resolve_pixel(world, *source.ids, source.resolve, x, y, ray, stats)
                      : world.intersect(ray);
}

// The primary hits of tile r: camera rays in packets (ray mode) or the id image resolved
// (hybrid); pixel (x, y)'s into hits[(y − r.y0)·stride + (x − r.x0)] (a tile's own buffer, or
// the whole image's at the tile's corner with stride = the image's width). Where `rays` is
// given, each pixel's camera ray goes to the same place in it, for the shading that follows
// (shade_tile), so that no pixel's ray is made twice.
void tile_primary_hits(const World& world, const PrimarySource& source, const TileRect& r,
                       Hit* hits, std::size_t stride, PrimaryStats& stats, Ray* rays = nullptr);

// Every pixel's primary hit from `source`, row-major, top row first.
std::vector<Hit> primary_hits(const World& world, const PrimarySource& source, PrimaryStats& stats,
                              const TileProgress& progress = {});

// Ray mode: every pixel's camera ray.
inline std::vector<Hit> primary_hits_by_ray(const World& world, const TileProgress& progress = {}) {
    PrimaryStats unused;
    return primary_hits(world, {}, unused, progress);
}

} // namespace GLINT_PRECISION
} // namespace glint
