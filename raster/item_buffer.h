// The item buffer (Ray Tracing III's last speed-up): every object drawn with its id into a
// GL_R32UI image (object index + 1) with a 32-bit float reverse-Z depth, from exactly the
// tracer's pinhole camera, then read back as an IdImage for trace/ to resolve. Which triangle of
// a tessellation was drawn is not kept: the resolve intersects the named object exactly, and a
// mesh's own triangle comes with that hit (Hit::primitive).
#pragma once

#include "trace/image.h"
#include "trace/names.h"
#include "trace/primary_hits.h"

#include <memory>
#include <string_view>
#include <vector>

namespace glint {

// mesh: tessellated (conservative) primitives; proxy: each analytic primitive's bounding box,
// whose fragments intersect the true primitive (exact ids, no tessellation error); automatic
// ("auto"): per object, whichever the cost model below says is cheaper to draw.
enum class RasterMode { mesh, proxy, automatic };

template <> struct EnumNames<RasterMode> {
    static constexpr auto names = name_table("mesh", "proxy", "auto");
};

// The raster cost model (docs/ITEM_BUFFER.md, "Mesh or proxy"), in seconds on llvmpipe with two
// cores: a triangle set up, and a pixel of the object's projected bounds filled, by a
// tessellation (the mesh shader) and by a proxy box (the proxy shader, which intersects the ray
// per fragment, front and back faces alike, and writes its depth).
struct RasterCosts {
    double triangle = 170e-9;
    double mesh_pixel = 10e-9;
    double proxy_pixel = 55e-9;
};
// Whether drawing an object as a proxy box (12 triangles) costs less than its tessellation of
// `triangles` triangles, when its bounds cover `pixels` pixels of the image.
inline bool proxy_is_cheaper(double triangles, double pixels, const RasterCosts& costs = {}) {
    return 12 * costs.triangle + pixels * costs.proxy_pixel <
           triangles * costs.triangle + pixels * costs.mesh_pixel;
}

struct ItemBufferResult {
    IdImage ids;
    Image flat; // with draw(world, true): each object's diffuse colour, flat-shaded by facet
};

class ItemBuffer {
  public:
    // Needs a current GL context (raster/gl_context.h); compiles the shaders.
    ItemBuffer();
    ~ItemBuffer();
    ItemBuffer(const ItemBuffer&) = delete;
    ItemBuffer& operator=(const ItemBuffer&) = delete;

    // Tessellates (mesh mode) and uploads what `world` needs drawn. `tessellation` is the number
    // of segments around curved outlines.
    void upload(const World& world, RasterMode mode, int tessellation);

    // Draws the uploaded objects from the world's camera and reads back ids and depth, and with
    // `flat_preview` also a flat-shaded colour image in the same pass (glint preview's first look).
    // With `samples` = N > 1, at N× the camera's width and height: the ids of every pixel's N×N
    // sample grid (trace/primary_hits.h, PrimarySource::sample_ids). Throws GlError where that
    // exceeds GL's largest target (16384 on llvmpipe).
    ItemBufferResult draw(const World& world, bool flat_preview = false, int samples = 1);

    // Per object, in world units: how far what was drawn may lie from the true surface.
    const std::vector<float>& deviations() const { return deviations_; }
    // How many objects the last upload draws as proxy boxes, and as tessellations.
    std::size_t proxies() const { return proxies_; }
    std::size_t tessellated() const { return tessellated_; }
    // Item buffers drawn since construction (draw() calls): what reuse saves is counted here.
    std::size_t draws() const { return draws_; }

    // Draws one triangle (camera-relative positions) with the given id, for tests of the id
    // round trip beyond 2^24.
    ItemBufferResult draw_triangle_for_test(const World& world, const Vec3 (&corners)[3],
                                            std::uint32_t object_id);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::vector<float> deviations_;
    std::size_t proxies_ = 0, tessellated_ = 0, draws_ = 0;
};

} // namespace glint
