// What max_depth and min_reflectivity may cost (adaptive depth): each ray a pixel's ray tree did
// not cast (a reflection or transmission) would have added its path weight times the radiance
// it sees, which the scene bounds; the render sums those weights per pixel. So a render carries
// its own error bound against the untruncated image, pixel by pixel, without casting a single
// extra ray.
#pragma once

#include "trace/render_result.h"
#include "trace/scene.h"

#include <cstdint>
#include <vector>

namespace glint {

// The most any ray can see, per channel, with secondary rays followed forever: every hit adds at
// most L = ambient_m·ambient + Σ_lights colour·(diffuse_m + specular_m) (n·l ≤ 1, the specular
// lobe ≤ 1, shadows through glass only dim it; a checker's colours count as the material's),
// or the background; each hit's secondary rays weigh at most r = the largest reflectivity +
// transmission, so the radiance is at most L_max / (1 − r). Infinite when r ≥ 1 (and anything
// is lit).
glm::dvec3 ray_radiance_bound(const Scene& scene);

struct CutoffBound {
    // Per pixel, in 1/255 steps: how far the pixel may be below its untruncated value. The
    // omitted term is never negative, so the truncated pixel is never above it, and a channel
    // already at 255 cannot rise: min(255 − value, ceil(255 · weight · bound)) over channels.
    // Empty where every pixel's is 0 (no material reflects or transmits), or where only the
    // figures below were asked for (cutoff_summary).
    std::vector<std::uint8_t> per_pixel;
    int max = 0;                       // largest per_pixel
    std::uint64_t pixels_over_one = 0; // pixels whose bound exceeds 1/255
    double largest_omitted_weight = 0; // the largest of the pixels' summed omitted weights
};

CutoffBound cutoff_bound(const Scene& scene, const RenderResult& render);
// Its figures alone (max, pixels_over_one, largest_omitted_weight), per_pixel left empty: what
// a render's report prints, without a byte a pixel to first-touch after the write.
CutoffBound cutoff_summary(const Scene& scene, const RenderResult& render);

// Per pixel, in radiance: the most the omitted rays could have added to any channel of the
// pixel's unclamped colour (its summed omitted weight times the largest channel of
// ray_radiance_bound): 0 where nothing was omitted, +inf where the scene's bound is infinite.
// The `cutoff` AOV of an EXR (io/exr.h).
std::vector<float> cutoff_radiance(const Scene& scene, const RenderResult& render);

// Channels of `truncated` (the render the bound was made for) not within [0, bound] below the
// same render untruncated (same rays, no cut-off): 0 when the bound holds. An empty per_pixel
// bounds every pixel by 0.
std::uint64_t cutoff_violations(const CutoffBound& bound, const Image& truncated,
                                const Image& untruncated);

} // namespace glint
