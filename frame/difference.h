// Two settings of one scene compared pixel by pixel (`glint compare --a … --b …`, `glint explain
// --against`, docs/DIFFERENCES.md): both frames rendered, the pixels that
// differ found, and each of those traced again on both sides with the recorder on, so that the
// first place its two ray trees part names its cause (trace/ray_tree.h, DESIGN §13). Only the
// differing pixels are traced again: what that costs is measured (`seconds` below).
#pragma once

#include "frame/frame.h"
#include "trace/explain.h"
#include "trace/ray_tree.h"

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint {

// One side of a comparison: the shared scene with this side's render settings, and its frame's.
struct Side {
    std::string label; // as given, for people: "--max-depth 2", "exact"
    Scene scene;
    std::optional<AccelKind> accel;
    FrameSettings frame;
    // The frame was rendered smaller and enlarged to the scene's size (`glint tradeoff`'s size
    // knob): none of its pixels took the samples a full-size pixel takes.
    bool resampled = false;
};

// The exact image's settings, as `glint tradeoff` renders it: ray traced in double precision,
// reflections followed to kMaxDepth, no weight cut-off.
void make_exact(Side& side);

// One line for people: "ray double, depth 64, no cut-off, bvh".
std::string describe_side(const Side& side);

// A side rendered, with what tracing its pixels again needs: its World (float), or a tracer of
// its own precision (double).
class RenderedSide {
  public:
    // Renders the side's frame; times.prepare counts its World's preparation in either precision.
    explicit RenderedSide(Side side);
    // A frame rendered already with the side's settings (`glint tradeoff` measures its runs
    // first); `geometry`: the scene's, prepared already (float), or null.
    RenderedSide(Side side, Frame frame, const std::shared_ptr<const SceneGeometry>& geometry);
    // Traced here on a World prepared already for the side's scene (float) and, in hybrid mode,
    // the item buffer drawn for it elsewhere (the preview draws with its window's GL; no GL
    // context is made here, so this may run beside one on another thread).
    RenderedSide(Side side, std::shared_ptr<const World> world, std::shared_ptr<const IdImage> ids);
    ~RenderedSide();
    RenderedSide(RenderedSide&&) noexcept;

    const Side& side() const { return side_; }
    const Frame& frame() const { return frame_; }
    // Gives the frame back (the side can trace no pixel after).
    Frame take_frame() && { return std::move(frame_); }
    // The pixels' trees (row-major indices into the frame), as the frame traced them; `depths`:
    // per pixel, a maximum depth below the side's to trace it to (empty: the side's).
    std::vector<PixelTrees> trees(std::span<const std::uint32_t> pixels,
                                  std::span<const int> depths = {}) const;
    // The samples pixel p took a side: N (its N×N grid), 1 (its centre), 0 (resampled).
    int grid_at(std::uint32_t p) const;

  private:
    Side side_;
    std::shared_ptr<const World> world_;                // float precision
    std::shared_ptr<const IdImage> ids_;                // an item buffer drawn elsewhere, if any
    mutable std::unique_ptr<DepthWorlds> depth_worlds_; // float: made as trees() asks for them
    std::unique_ptr<PixelTracer> tracer_;               // double precision
    Frame frame_;
};

// Per cause: how many pixels, their error, and at which level the trees parted.
struct CauseTally {
    std::uint64_t pixels = 0;
    double squared_error = 0; // Σ over its pixels and channels of (a − b)², linear radiance
    double largest = 0;       // the largest channel difference of its pixels
    std::vector<std::uint64_t> levels; // depth, cutoff, secondary: pixels by level (index 0: 0)
};

struct FrameDifference {
    int width = 0, height = 0;
    std::vector<Cause> causes; // per pixel, row-major; none where the pixel does not differ
    std::vector<float> error;  // per pixel: the largest channel difference in linear radiance
    std::array<CauseTally, kCauses> tallies; // indexed by Cause; none's stays empty
    std::uint64_t differing = 0;
    double squared_error = 0; // over the differing pixels: the tallies' sum
    double largest = 0;       // the largest error of any pixel
    std::uint64_t traced = 0; // differing pixels traced again (the rest: their grids differ)
    double trace_seconds = 0; // tracing them again on both sides
    // A cause's share of the squared radiance error of the differing pixels (by pixels where
    // that error is 0: pixels whose bytes differ while their radiance agrees).
    double share(Cause cause) const;
};

// Compares the two frames: a pixel differs where its PNG bytes do, and with `radiance` also
// where its radiance does (a float output's); each differing pixel's cause from its trees, traced
// again on both sides, or `sampling` without tracing where its grids differ (grid_at).
FrameDifference difference(const RenderedSide& a, const RenderedSide& b, bool radiance);

// One pixel: its cause (none where its bytes, and with `radiance` its radiance, agree), from its
// trees on both sides.
Divergence pixel_difference(const PixelTrees& a, const PixelTrees& b, bool radiance);

} // namespace glint
