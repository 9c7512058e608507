// One pixel explained (`glint explain`, the preview's click): the ray tree of one of its samples
// as the renderer's own path computed it (trace/pixel.h with a RayRecorder, trace/recorder.h),
// what the item buffer said there and how the resolve went, and the byte values the render
// writes. docs/EXPLAIN.md shows it at work.
#pragma once

#include "trace/primary_hits.h"
#include "trace/ray_tree.h"
#include "trace/recorder.h"
#include "trace/render_result.h"

#include <array>
#include <map>
#include <memory>
#include <optional>

namespace glint {
inline namespace GLINT_PRECISION {

// What the item buffer said at a sample, and how the exact resolve (trace/primary_hits.h) went.
struct ItemBufferVerdict {
    std::uint32_t id = 0; // object + 1; 0: nothing drawn
    float view_depth = 0; // of what was drawn there
    PrimaryStats resolve; // this sample's share of the counters: which steps it took
    // The pixel centre's verdict in adaptive antialiasing's first pass, for a refined pixel whose
    // grid was traced by ray (trace/sampling.h: without rule 3 no N×N item buffer is drawn).
    bool first_pass = false;
    // In words: "direct" (the named object's exact hit, nothing nearer), "corrected" (a nearer
    // object was found), "fallback" (the named object was missed: traced in full), "background"
    // (nothing drawn, nothing there), "traced" (nothing drawn, the ray found something).
    const char* outcome() const;
};

// A hit a ray passed through because its material cuts out there (DESIGN §13).
struct CutThrough {
    std::uint32_t object;
    Real t;
    float alpha, cutoff; // alpha < cutoff
};

struct PixelExplanation {
    int x = 0, y = 0;              // the pixel
    int n = 1;                     // its N×N grid (the scene's samples)
    int a = 0, b = 0;              // the sample explained: column and row in the grid
    std::vector<RecordedRay> rays; // its tree, the primary ray first, depth first
    // Per ray that hit something: the ray in its object's space, M⁻¹·origin (w = 1) and
    // M⁻¹·direction (w = 0), as the intersection routine saw it; unset for misses.
    std::vector<Ray> object_rays;
    // Per ray, per light (as in rays[i].lights): the first opaque object on the blocked shadow
    // segment, kNoObject where the light is not blocked.
    std::vector<std::vector<std::uint32_t>> blockers;
    // Per ray: the cut-out objects it passed through before its hit, nearest first (each
    // object's nearest such hit).
    std::vector<std::vector<CutThrough>> cut_through;
    std::optional<ItemBufferVerdict> item_buffer; // hybrid only
    RayCounts tree_rays; // the rays of `rays`, shadow rays included: the explained sample's
    std::array<std::uint8_t, 3> sample_bytes{};
    // The pixel as the render writes it: the sample itself (N = 1, or adaptive antialiasing
    // where the pixel was not refined) or its grid's mean.
    bool averaged = false;
    Vec3 pixel_colour{0}; // the mean of the clamped samples, or the sample's colour unclamped
    RayCounts pixel_rays; // as the render counts them for the pixel (every sample of a grid)
    std::array<std::uint8_t, 3> pixel_bytes{};
};

// Explains sample (a, b) of pixel (x, y) (both in range: the caller checks), whose primary hits
// come from `source` as in the render. `refined`: adaptive antialiasing refined this pixel (the
// render's RenderResult::refined); ignored unless the scene is adaptive with N > 1.
PixelExplanation explain_pixel(const World& world, const PrimarySource& source, int x, int y, int a,
                               int b, bool refined = false);

// Every sample's tree of pixel (x, y) as the render traces it from `source` (trace/ray_tree.h):
// the grid's N² samples where the pixel takes its grid, else its centre's one. `refined` as above.
PixelTrees pixel_trees(const World& world, const PrimarySource& source, int x, int y,
                       bool refined = false);

// Worlds of one scene at lower maximum depths than its own, each made on first use and kept
// (they share the scene's World's geometry). Not for several threads at once.
class DepthWorlds {
  public:
    // `world` is made from `scene`; both must outlive this.
    DepthWorlds(const Scene& scene, const World& world) : scene_(scene), world_(world) {}
    // The World at `depth`: the scene's own at or above its depth.
    const World& at(int depth);

  private:
    const Scene& scene_;
    const World& world_;
    std::map<int, std::unique_ptr<World>> capped_;
};

// pixel_trees for many pixels (row-major indices) of `worlds`' scene, in parallel. `refined`:
// adaptive antialiasing's verdict per pixel of the frame (empty: none). `depths`: per pixel, a
// maximum depth below the scene's to trace it to (empty: the scene's).
std::vector<PixelTrees> many_pixel_trees(DepthWorlds& worlds, const PrimarySource& source,
                                         std::span<const std::uint32_t> pixels,
                                         std::span<const std::uint8_t> refined,
                                         std::span<const int> depths);

} // namespace GLINT_PRECISION
} // namespace glint
