// A tile's shading, the one step every pass of a frame ends with (trace/passes.h): each pixel
// shaded from its primary hit through trace/pixel.h's path, its shadow rays cast in packets of
// neighbours, and stored into the frame's float images, ids and AOVs.
#pragma once

#include "trace/pixel.h"
#include "trace/render_result.h"

#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

// Shown every pixel the centres pass traces, with what its path found (the preview's views).
class CentreObserver {
  public:
    virtual void pixel(int x, int y, const Ray& ray, const PixelSample& sample) = 0;

  protected:
    ~CentreObserver() = default;
};

// Writes a shaded colour as a pixel's three bytes (trace/image.h's to_byte per channel).
inline void store_colour(Vec3 c, std::uint8_t* pixel) {
    for (int i = 0; i < 3; ++i) pixel[i] = to_byte(static_cast<float>(c[i]));
}

// Stores pixel i's colour, the mean of its samples: unclamped, and with each sample clamped
// (with one sample, the colour clamped), the latter kept apart where N > 1; or, where the
// result keeps no floats, the bytes of the clamped one, which are display()'s (to_byte clamps
// what it is given: the two agree on every float, NaN included).
inline void store_pixel(RenderResult& result, std::size_t i, Vec3 radiance, Vec3 clamped) {
    if (!result.floats()) {
        for (int k = 0; k < 3; ++k)
            result.display_bytes.rgb[3 * i + k] = to_byte(static_cast<float>(clamped[k]));
        return;
    }
    result.radiance.set(i, radiance);
    if (!result.clamped.empty()) result.clamped.set(i, clamped);
}

// Stores what pixel i's centre ray hit, where the result keeps its AOVs.
inline void store_aovs(RenderResult& result, std::size_t i, const Hit& hit, Vec3 normal) {
    if (result.aovs.empty() || !hit.found()) return;
    result.aovs.depth[i] = static_cast<float>(hit.t);
    for (int k = 0; k < 3; ++k) result.aovs.normal[3 * i + k] = static_cast<float>(normal[k]);
    result.aovs.id[i] = hit.object + 1;
}

// What a frame keeps besides its pixels' colours (trace/passes.h's run_frame reads it).
struct FrameRequest {
    bool aovs = false;          // keep each pixel centre's primary hit (RenderResult::aovs)
    // Keep each pixel's object id (RenderResult::ids): what compare, tradeoff and the MPI
    // exchange read. A plain render reads none, and leaves the layer out.
    bool ids = true;
    // Keep the float images (RenderResult::radiance, clamped): what an EXR, compare, tradeoff,
    // the preview, the Python module and the MPI exchange read. false: the display bytes alone
    // (RenderResult::display_bytes), all a PNG and its report read.
    bool radiance = true;
    bool centres_first = false; // uniform grids too start with a centres pass (a first look)
    CentreObserver* observer = nullptr;
};

// An empty result for `world`'s image: the float images (the clamped one where a pixel's
// samples are N > 1), or the display bytes alone where `request` asks for no radiance; the
// cut-off weights where a material reflects or transmits; the AOVs and the ids where `request`
// asks for them.
RenderResult blank_result(const World& world, int samples, const FrameRequest& request);

// A worker thread's buffers for the tile it works on, kept from tile to tile (tile_buffers()).
// Allocated anew for each tile, they cost small scenes up to two thirds of their shading time:
// glibc gives the free memory at the top of its heap back to the kernel once more than 128 KB
// lie there, and the next tile's first touch of each of those pages is a page fault
// (docs/PERFORMANCE.md, "Tile buffers and huge pages").
struct TileBuffers {
    std::vector<Hit> primary;        // the centres pass: the tile's primary hits
    std::vector<Ray> primary_rays;   // and their camera rays
    std::vector<std::size_t> pixels; // the pixels being shaded, in the order shaded
    std::vector<Ray> rays;           // their camera rays
    std::vector<Hit> hits;           // their primary hits (the grids pass: grid after grid)
    TileLighting lighting;           // their surfaces and shadow verdicts
};

// The calling thread's TileBuffers. A tile's work uses them until it returns; a thread works on
// one tile at a time (nothing in a tile's work waits on other tasks, so none is run meanwhile).
TileBuffers& tile_buffers();

// Shades tile r's pixels from their primary hits (pixel (x, y)'s at primary[(y − r.y0)·stride +
// (x − r.x0)], as tile_primary_hits leaves them) into `result`: colour, cut-off weight, id, AOVs
// where kept, and with `path_keys` each pixel's RayTree::path_key; shows each to `observer`
// where given. Returns the rays cast. The pixels go in blocks, so that their shadow rays go in
// packets of neighbours (TileLighting). Their camera rays are read from `camera_rays` (laid out
// as `primary`) where tile_primary_hits kept them, else made again.
RayCounts shade_tile(const World& world, const Hit* primary, std::size_t stride, const TileRect& r,
                     RenderResult& result, std::vector<std::uint64_t>* path_keys,
                     CentreObserver* observer = nullptr, const Ray* camera_rays = nullptr);

} // namespace GLINT_PRECISION
} // namespace glint
