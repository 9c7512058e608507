// Antialiasing (DESIGN §11, docs/ANTIALIASING.md): the N×N grid of samples in a pixel, each
// through the one pixel path (trace/pixel.h), and the adaptive rule that decides which pixels
// need the grid. trace/passes.h runs them as a frame's passes.
#pragma once

#include "trace/pixel.h"

#include <algorithm>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

// The adaptive rule, from a first pass of one sample per pixel (the pixel centre, N = 1's image):
// pixel p takes its N×N grid when
//   1. any of its 8 neighbours q has another path key (trace/shading.h's RayTree::path_key: a
//      different object, background or checker cell along the path, or another shadow
//      verdict), or
//   2. any channel of p's and q's bytes differs by more than threshold · 255, or
//   3. (hybrid) the N×N item buffer's ids inside p are not all one id: an edge, or an object too
//      thin for the pixel centre to see, falls inside the pixel.
// Rules 1 and 2 read only the first pass, which exact hybrid and ray mode trace alike; rule 3
// only adds pixels. `sample_ids` is the N×N item buffer (N·width × N·height), or null.
std::vector<std::uint8_t> adaptive_refinement(const Image& first,
                                              const std::vector<std::uint64_t>& path_keys,
                                              const IdImage* sample_ids, int n, float threshold);

// The rule's last part, applied after each round of refinement until it adds nothing (at most
// kMaxSpreadRounds rounds):
//   4. an unrefined pixel next to (8-neighbour of) a refined pixel whose grid's mean, in
//      `current`, differs from its one-sample colour in `first` by more than threshold · 255 in
//      any channel: detail finer than the pixel spacing that the first pass aliased away (a
//      checker seen far off or through glass), which spreads until it is enclosed.
// Returns the pixels to refine next (1), and none when the rule adds nothing.
std::vector<std::uint8_t> adaptive_spread(const Image& first, const Image& current,
                                          const std::vector<std::uint8_t>& refined, float threshold,
                                          std::size_t& added);
inline constexpr int kMaxSpreadRounds = 16;

// The primary hits of pixel (x, y)'s N×N samples (N = world.settings().samples) into hits[0…N²),
// b outer, a inner: from source.sample_ids when given, else by camera ray.
void grid_hits(const World& world, const PrimarySource& source, int x, int y, Hit* hits,
               PrimaryStats& stats);

// A pixel from its grid: each sample shaded through trace/pixel.h's path, its colour clamped to
// [0, 1], the clamped colours summed row of samples by row and divided by N².
struct GridPixel {
    Vec3 mean{0};     // of the clamped samples: what a display shows
    Vec3 radiance{0}; // of the samples unclamped: what an HDR file keeps
    RayCounts rays;
    Real omitted_weight = 0;     // the samples' mean (trace/cutoff.h)
    std::uint32_t centre_id = 0; // sample (N/2, N/2)'s object + 1, 0 for background
};
// With `recorder`, sample `recorded` (b·N + a) reports its ray tree there (trace/recorder.h).
GridPixel shade_grid(const World& world, int x, int y, const Hit* hits,
                     RayRecorder* recorder = nullptr, int recorded = -1);

// Rule 4's rounds: while adaptive_spread finds pixels to add (at most kMaxSpreadRounds times),
// refine(next) puts their grids' means into `current` (it returns false to stop: cancelled),
// and they are marked in `refined`. Where the image is spread over processes, only the one that
// `decides` holds `first` and `current` whole and runs adaptive_spread; agree(next) gives its
// round to every process (in one process, agree does nothing). Returns how many pixels it added.
template <class Agree, class Refine>
std::size_t spread_refinement(const Image& first, const Image& current,
                              std::vector<std::uint8_t>& refined, float threshold, bool decides,
                              const Agree& agree, const Refine& refine) {
    std::size_t total = 0;
    for (int round = 0; round < kMaxSpreadRounds; ++round) {
        std::size_t added = 0;
        std::vector<std::uint8_t> next;
        if (decides) next = adaptive_spread(first, current, refined, threshold, added);
        agree(next);
        if (!decides) added = static_cast<std::size_t>(std::count(next.begin(), next.end(), 1));
        if (added == 0 || !refine(next)) break;
        for (std::size_t i = 0; i < next.size(); ++i) refined[i] |= next[i];
        total += added;
    }
    return total;
}

} // namespace GLINT_PRECISION
} // namespace glint
