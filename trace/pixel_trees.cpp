// A pixel's ray trees as the render traces them (trace/ray_tree.h), in the precision of the
// library that compiles this file: the recorder's nodes (trace/recorder.h) in the form both
// precisions share.
#include "trace/explain.h"
#include "trace/pixel.h"
#include "trace/sampling.h"

#include <tbb/parallel_for.h>

#include <limits>

namespace glint {
inline namespace GLINT_PRECISION {

namespace {

Verdict verdict_of(const LightTerm& term) {
    if (!term.in_front()) return Verdict::behind;
    if (term.through == 0) return Verdict::blocked;
    return term.through == 1 ? Verdict::lit : Verdict::through_glass;
}

Stop stop_of(OmittedRay::Why why) {
    switch (why) {
    case OmittedRay::Why::max_depth:
        return Stop::max_depth;
    case OmittedRay::Why::min_weight:
        return Stop::min_weight;
    case OmittedRay::Why::tree_budget:
        break;
    }
    return Stop::tree_budget;
}

SampleTree tree_of(const std::vector<RecordedRay>& rays) {
    SampleTree tree(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const RecordedRay& ray = rays[i];
        TreeNode& node = tree[i];
        node.kind = ray.kind, node.depth = ray.depth;
        node.object = ray.hit.found() ? ray.hit.object : kNoObject;
        for (const LightTerm& term : ray.lights) node.lights.push_back(verdict_of(term));
        node.weight = static_cast<double>(ray.weight);
        node.colour = DVec3(ray.colour);
        node.own = node.colour;
        for (const int c : ray.children) {
            const int k = rays[static_cast<std::size_t>(c)].kind == RayKind::transmission;
            node.child[static_cast<std::size_t>(k)] = c,
            node.stop[static_cast<std::size_t>(k)] = Stop::cast;
            node.own -= static_cast<double>(rays[static_cast<std::size_t>(c)].factor) *
                        DVec3(rays[static_cast<std::size_t>(c)].colour);
        }
        for (const OmittedRay& omitted : ray.omitted)
            node.stop[omitted.kind == RayKind::transmission] = stop_of(omitted.why);
    }
    return tree;
}

std::array<std::uint8_t, 3> bytes_of(Vec3 display) {
    std::array<std::uint8_t, 3> bytes{};
    for (int i = 0; i < 3; ++i)
        bytes[static_cast<std::size_t>(i)] = to_byte(static_cast<float>(display[i]));
    return bytes;
}

} // namespace

PixelTrees pixel_trees(const World& world, const PrimarySource& source, int x, int y,
                       bool refined) {
    const RenderSettings& settings = world.settings();
    const int n = settings.samples;
    PixelTrees out;
    PrimaryStats stats;
    if (n > 1 && (settings.antialias == Antialias::uniform || refined)) {
        out.grid = n;
        std::vector<Hit> hits(static_cast<std::size_t>(n) * n);
        grid_hits(world, source, x, y, hits.data(), stats);
        // The pixel's colour from the render's own arithmetic; then each sample again, recorded.
        const GridPixel pixel = shade_grid(world, x, y, hits.data());
        out.radiance = DVec3(pixel.radiance);
        out.bytes = bytes_of(pixel.mean);
        for (int b = 0; b < n; ++b)
            for (int a = 0; a < n; ++a) {
                RayRecorder recorder;
                shade_pixel(world, world.camera().sample_ray(x, y, a, b, n),
                            hits[static_cast<std::size_t>(b * n + a)], {}, &recorder);
                out.samples.push_back(tree_of(recorder.rays()));
            }
        return out;
    }
    RayRecorder recorder;
    const Ray ray = world.camera().ray(x, y);
    const PixelSample sample =
        shade_pixel(world, ray, primary_hit(world, source, x, y, ray, stats), {}, &recorder);
    out.radiance = DVec3(sample.colour);
    out.bytes = bytes_of(sample.colour);
    out.samples.push_back(tree_of(recorder.rays()));
    return out;
}

const World& DepthWorlds::at(int depth) {
    if (depth >= world_.settings().max_depth) return world_;
    std::unique_ptr<World>& capped = capped_[depth];
    if (!capped) {
        Scene copy = scene_;
        copy.render.max_depth = depth;
        capped = std::make_unique<World>(copy, world_);
    }
    return *capped;
}

std::vector<PixelTrees> many_pixel_trees(DepthWorlds& worlds, const PrimarySource& source,
                                         std::span<const std::uint32_t> pixels,
                                         std::span<const std::uint8_t> refined,
                                         std::span<const int> depths) {
    const World& own = worlds.at(std::numeric_limits<int>::max());
    std::vector<const World*> world_of(pixels.size(), &own);
    for (std::size_t i = 0; i < depths.size(); ++i) world_of[i] = &worlds.at(depths[i]);
    const auto width = static_cast<std::uint32_t>(own.camera().width());
    std::vector<PixelTrees> out(pixels.size());
    tbb::parallel_for(std::size_t{0}, pixels.size(), [&](std::size_t i) {
        const std::uint32_t p = pixels[i];
        out[i] = pixel_trees(*world_of[i], source, static_cast<int>(p % width),
                             static_cast<int>(p / width), !refined.empty() && refined[p] != 0);
    });
    return out;
}

namespace {

class RayPixelTracer final : public PixelTracer {
  public:
    RayPixelTracer(const Scene& scene, std::optional<AccelKind> accel)
        : scene_(scene), world_(scene, accel), worlds_(scene_, world_) {}

    std::vector<PixelTrees> trees(std::span<const std::uint32_t> pixels,
                                  std::span<const std::uint8_t> refined,
                                  std::span<const int> depths) const override {
        return many_pixel_trees(worlds_, {}, pixels, refined, depths);
    }

  private:
    Scene scene_;
    World world_;
    mutable DepthWorlds worlds_; // made as trees() asks for them
};

} // namespace

std::unique_ptr<PixelTracer> ray_pixel_tracer(const Scene& scene, std::optional<AccelKind> accel) {
    return std::make_unique<RayPixelTracer>(scene, accel);
}

} // namespace GLINT_PRECISION
} // namespace glint
