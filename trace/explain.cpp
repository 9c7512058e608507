#include "trace/explain.h"

#include "trace/render.h"
#include "trace/sampling.h"
#include "trace/shading.h"

#include <algorithm>

namespace glint {
inline namespace GLINT_PRECISION {

const char* ItemBufferVerdict::outcome() const {
    if (resolve.fallbacks > 0) return "fallback";
    if (resolve.corrected > 0) return "corrected";
    if (id == 0) return resolve.traced > 0 ? "traced" : "background";
    return "direct";
}

namespace {

// The first opaque object on the shadow segment from `surface` to `light` (which shading found
// blocked): walked crossing by crossing, as light_through (trace/shading.cpp) does through glass.
std::uint32_t first_blocker(const World& world, const SurfacePoint& surface, Vec3 light) {
    Ray segment = shadow_ray(surface, light);
    std::uint32_t skip = surface.skip;
    for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        const Hit hit = world.intersect(segment, 1.0_r, skip);
        if (!hit.found()) break;
        if (world.material(hit.object).transmission == 0) return hit.object;
        const SurfacePoint crossed = world.surface(segment, hit);
        segment = {crossed.spawn_through(), light - crossed.spawn_through()};
        skip = crossed.skip_through;
    }
    return kNoObject; // only glass: blocked by the crossing limit
}

// Each cut-out object's nearest hit on `ray` before `t_hit` when it is cut away there: the mesh
// intersected as if nothing were cut, then its hit's alpha read as the tracer reads it.
std::vector<CutThrough> cut_through(const World& world, const Ray& ray, Real t_hit) {
    std::vector<CutThrough> passed;
    for (std::uint32_t i = 0; i < world.objects().size(); ++i) {
        const Object& o = world.objects()[i];
        if (!o.params.cut_out) continue;
        NoCounters none;
        const ShapeHit h = intersect_mesh(*o.params.mesh, o.transform.to_object(ray), t_hit, none);
        const CutOut& cut = *o.params.cut_out;
        if (h.found() && cut_away(*o.params.mesh, cut, h.part, h.u, h.v))
            passed.push_back(
                {i, h.t, cut_out_alpha(*o.params.mesh, cut, h.part, h.u, h.v), cut.cutoff});
    }
    std::sort(passed.begin(), passed.end(),
              [](const CutThrough& a, const CutThrough& b) { return a.t < b.t; });
    return passed;
}

std::array<std::uint8_t, 3> bytes_of(Vec3 colour) {
    std::array<std::uint8_t, 3> bytes{};
    store_colour(colour, bytes.data());
    return bytes;
}

} // namespace

PixelExplanation explain_pixel(const World& world, const PrimarySource& source, int x, int y, int a,
                               int b, bool refined) {
    const RenderSettings& settings = world.settings();
    PixelExplanation out;
    out.x = x, out.y = y, out.n = settings.samples, out.a = a, out.b = b;
    const int n = settings.samples;
    const bool grid = n > 1 && (settings.antialias == Antialias::uniform || refined);
    const bool ids = grid ? source.sample_ids != nullptr : source.ids != nullptr;
    RayRecorder recorder;
    PrimaryStats stats;
    if (grid) {
        // The grid's hits as the render finds them; the explained sample resolved again on its
        // own (the same answer) for its share of the counters.
        std::vector<Hit> hits(static_cast<std::size_t>(n) * n);
        PrimaryStats all;
        grid_hits(world, source, x, y, hits.data(), all);
        if (ids)
            resolve_pixel(world, *source.sample_ids, source.resolve, x * n + a, y * n + b,
                          world.camera().sample_ray(x, y, a, b, n), stats);
        const GridPixel pixel = shade_grid(world, x, y, hits.data(), &recorder, b * n + a);
        out.averaged = true;
        out.pixel_colour = pixel.mean, out.pixel_rays = pixel.rays;
    } else {
        // One sample: N = 1, or adaptive antialiasing's first pass where the pixel was not
        // refined (the centre sample's ray is the pixel centre's).
        if (n > 1) out.a = out.b = n / 2;
        const Ray ray = world.camera().ray(x, y);
        const PixelSample sample =
            shade_pixel(world, ray, primary_hit(world, source, x, y, ray, stats), {}, &recorder);
        out.pixel_colour = sample.colour, out.pixel_rays = sample.rays;
    }
    out.rays = recorder.rays();
    out.pixel_bytes = bytes_of(out.pixel_colour);
    // The explained sample's own tally and bytes, from its tree as recorded.
    const RecordedRay& primary = out.rays.front();
    out.sample_bytes = bytes_of(primary.colour);
    for (const RecordedRay& ray : out.rays) {
        out.object_rays.push_back(
            ray.hit.found() ? world.objects()[ray.hit.object].transform.to_object(ray.ray) : Ray{});
        ++(ray.kind == RayKind::primary      ? out.tree_rays.primary
           : ray.kind == RayKind::reflection ? out.tree_rays.reflection
                                             : out.tree_rays.transmission);
        out.cut_through.push_back(cut_through(world, ray.ray, ray.hit.t));
        std::vector<std::uint32_t>& blockers = out.blockers.emplace_back();
        for (const LightTerm& term : ray.lights) {
            out.tree_rays.shadow += term.shadow_rays;
            blockers.push_back(
                term.in_front() && term.through == 0
                    ? first_blocker(world, ray.surface, world.lights()[term.light].position)
                    : kNoObject);
        }
    }
    if (ids) {
        const IdImage& image = grid ? *source.sample_ids : *source.ids;
        const std::size_t p =
            static_cast<std::size_t>(y * (grid ? n : 1) + (grid ? out.b : 0)) * image.width +
            static_cast<std::size_t>(x * (grid ? n : 1) + (grid ? out.a : 0));
        out.item_buffer = ItemBufferVerdict{image.ids[p], image.view_depth[p], stats};
    } else if (source.ids) { // a refined pixel traced by ray: what the first pass found
        PrimaryStats centre;
        resolve_pixel(world, *source.ids, source.resolve, x, y, world.camera().ray(x, y), centre);
        const std::size_t p = static_cast<std::size_t>(y) * source.ids->width + x;
        out.item_buffer =
            ItemBufferVerdict{source.ids->ids[p], source.ids->view_depth[p], centre, true};
    }
    return out;
}

} // namespace GLINT_PRECISION
} // namespace glint
