#include "trace/cutoff.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

glm::dvec3 ray_radiance_bound(const Scene& scene) {
    glm::dvec3 light_sum(0.0);
    for (const PointLight& light : scene.lights) light_sum += glm::dvec3(light.color);
    glm::dvec3 local = glm::dvec3(scene.background);
    if (scene.environment) // a ray that leaves returns at most the environment's brightest texel
        local = glm::max(local, glm::dvec3(scene.environment->brightest));
    double reflectivity = 0;
    for (const Material& m : scene.materials) {
        glm::dvec3 specular(m.specular);
        double reflects = m.reflectivity;
        const auto hit = [&](glm::dvec3 ambient, glm::dvec3 diffuse) {
            // Emission: its texture's texels are at most 1.
            return ambient * glm::dvec3(scene.ambient) + glm::dvec3(m.emission) +
                   light_sum * (diffuse + specular);
        };
        if (const std::optional<MetalRoughInputs>& p = m.metal_rough) {
            // Per texel (DESIGN §14), with texels at most 1: k_d at most b(1 − t) (no metal),
            // k_s the larger of 0.04 and b, the reflectivity the metallic factor's, k_a their sum.
            const glm::dvec3 b(p->base);
            const glm::dvec3 diffuse = b * double(1 - p->transmission) * double(p->coverage);
            specular = glm::max(glm::dvec3(0.04), b) * double(p->coverage);
            reflects = double(p->metallic) * p->coverage;
            local = glm::max(local, hit(diffuse + specular, diffuse));
        } else {
            local = glm::max(local, hit(glm::dvec3(m.ambient), glm::dvec3(m.diffuse)));
        }
        if (m.checker.size > 0)
            local =
                glm::max(local, hit(glm::dvec3(m.checker.ambient), glm::dvec3(m.checker.diffuse)));
        // A hit may cast both a reflected and a transmitted ray: their factors add.
        reflectivity = std::max(reflectivity, reflects + double(m.transmission));
    }
    if (reflectivity < 1) return local / (1 - reflectivity);
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {local.x > 0 ? inf : 0, local.y > 0 ? inf : 0, local.z > 0 ? inf : 0};
}

namespace {

// The bound's extremes, and its per-pixel steps where `per_pixel`.
CutoffBound bound_of(const Scene& scene, const RenderResult& render, bool per_pixel) {
    CutoffBound bound;
    // No layer: no material reflects or transmits, so no ray was omitted and the bound is 0.
    if (render.omitted_weight.empty()) return bound;
    const glm::dvec3 radiance = ray_radiance_bound(scene);
    if (per_pixel) bound.per_pixel.assign(render.omitted_weight.size(), 0);
    // In parallel bands of pixels (it runs after the frame's write, outside every timed phase:
    // docs/PERFORMANCE.md, "Start-up and the write"), each band's extremes joined after.
    struct Extremes {
        int max = 0;
        std::uint64_t pixels_over_one = 0;
        double largest_omitted_weight = 0;
    };
    const auto band = [&](const tbb::blocked_range<std::size_t>& r, Extremes partial) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const double weight = render.omitted_weight[i];
            partial.largest_omitted_weight = std::max(partial.largest_omitted_weight, weight);
            if (weight == 0) continue;
            int pixel = 0;
            for (int c = 0; c < 3; ++c) {
                const int headroom = 255 - render.byte_at(i, c);
                // (1 + 1e-6) absorbs the rounding of the weight and of the sums it is compared
                // with.
                const double steps = std::ceil(255 * weight * radiance[c] * (1 + 1e-6));
                pixel = std::max(pixel, steps < headroom ? static_cast<int>(steps) : headroom);
            }
            if (per_pixel) bound.per_pixel[i] = static_cast<std::uint8_t>(pixel);
            partial.max = std::max(partial.max, pixel);
            partial.pixels_over_one += pixel > 1;
        }
        return partial;
    };
    const auto join = [](Extremes a, const Extremes& b) {
        return Extremes{std::max(a.max, b.max), a.pixels_over_one + b.pixels_over_one,
                        std::max(a.largest_omitted_weight, b.largest_omitted_weight)};
    };
    const Extremes all = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, render.omitted_weight.size(), 1 << 16), Extremes{}, band,
        join);
    bound.max = all.max;
    bound.pixels_over_one = all.pixels_over_one;
    bound.largest_omitted_weight = all.largest_omitted_weight;
    return bound;
}

} // namespace

CutoffBound cutoff_bound(const Scene& scene, const RenderResult& render) {
    return bound_of(scene, render, true);
}

CutoffBound cutoff_summary(const Scene& scene, const RenderResult& render) {
    return bound_of(scene, render, false);
}

std::vector<float> cutoff_radiance(const Scene& scene, const RenderResult& render) {
    const glm::dvec3 radiance = ray_radiance_bound(scene);
    const double most = std::max({radiance.x, radiance.y, radiance.z});
    std::vector<float> out(render.pixels(), 0.0f);
    for (std::size_t i = 0; i < render.omitted_weight.size(); ++i)
        if (render.omitted_weight[i] > 0) out[i] = static_cast<float>(render.omitted_weight[i] * most);
    return out;
}

std::uint64_t cutoff_violations(const CutoffBound& bound, const Image& truncated,
                                const Image& untruncated) {
    std::uint64_t violations = 0;
    for (std::size_t i = 0; i < truncated.rgb.size() / 3; ++i) {
        const int allowed = bound.per_pixel.empty() ? 0 : bound.per_pixel[i];
        for (int c = 0; c < 3; ++c) {
            const int below = untruncated.rgb[3 * i + c] - truncated.rgb[3 * i + c];
            violations += below < 0 || below > allowed;
        }
    }
    return violations;
}

} // namespace glint
