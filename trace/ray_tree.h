// Two settings of one scene, one pixel: where their ray trees part, and so why the pixel differs
// (`glint compare --a … --b …`, `glint explain --against`, docs/DIFFERENCES.md). The trees come
// from the recorder (trace/recorder.h) in either precision and are kept here in one form both
// share, so that a float tree can be laid beside a double one. The rule is DESIGN §13's: walk both
// trees in the same order (the primary ray, then per node its shadow verdicts light by light, its
// reflected child, its transmitted child); the first place they part names the cause.
#pragma once

#include "trace/accel/accel_kind.h"
#include "trace/names.h"
#include "trace/recorder.h"
#include "trace/scene.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace glint {

// Why a pixel differs between two settings, in the order DESIGN §13 checks them; `none`: its
// bytes (and, for float outputs, its radiance) agree.
enum class Cause : std::uint8_t {
    none,
    sampling,  // the pixel took another sample grid (its size, or adaptive refinement)
    depth,     // one tree stops at its maximum depth where the other goes on
    cutoff,    // one tree stops at the weight cut-off (min reflectivity) where the other goes on
    primary,   // the primary ray hits another object, or none
    secondary, // a reflected or transmitted ray hits another object, or none
    shadow,    // a shadow verdict differs (blocked, lit, through glass, or the light behind)
    precision, // the trees match node for node; only the numbers differ
};
inline constexpr std::size_t kCauses = 8;

template <> struct EnumNames<Cause> {
    static constexpr auto names = name_table("none", "sampling", "depth", "cutoff", "primary",
                                             "secondary", "shadow", "precision");
};

// Why a reflected or transmitted ray was not cast (OmittedRay::Why), or `cast`; `none`: the
// material has no such ray.
enum class Stop : std::uint8_t { cast, max_depth, min_weight, tree_budget, none };

template <> struct EnumNames<Stop> {
    static constexpr auto names =
        name_table("cast", "max_depth", "min_weight", "tree_budget", "none");
};

// One light at a node, as the verdict the cause rule compares.
enum class Verdict : std::uint8_t { behind, blocked, lit, through_glass };

template <> struct EnumNames<Verdict> {
    static constexpr auto names = name_table("behind", "blocked", "lit", "glass");
};

// One node of a ray tree: a primary, reflected or transmitted ray.
struct TreeNode {
    RayKind kind = RayKind::primary;
    int depth = 0;                    // reflections and transmissions before it
    std::uint32_t object = kNoObject; // what it hit
    std::vector<Verdict> lights;      // at a hit: per light, in the scene's order
    std::array<int, 2> child{-1, -1}; // the reflected and the transmitted ray: node indices
    std::array<Stop, 2> stop{Stop::none, Stop::none}; // none: the material has no such ray
    double weight = 1; // the path weight: the factors' product down to here
    DVec3 colour{0};   // R_p, unclamped: what the ray brought back
    DVec3 own{0};      // its own terms (ambient, diffuse, specular), R_p less its children's share
    // The node's share of the sample's colour: weight · own. The shares of a tree sum to its
    // primary ray's colour.
    DVec3 share() const { return weight * own; }
};

// One sample's tree, the primary ray first, then depth first (reflected before transmitted).
using SampleTree = std::vector<TreeNode>;

// A pixel's trees as one setting renders it.
struct PixelTrees {
    int grid = 1;                        // the samples it took: grid × grid (1: its centre)
    std::vector<SampleTree> samples;     // row-major in the grid
    DVec3 radiance{0};                   // the pixel's colour: the samples' mean, unclamped
    std::array<std::uint8_t, 3> bytes{}; // what the PNG holds there
};

// The deepest node of a pixel's trees.
int deepest(const PixelTrees& trees);

// Where two pixels' trees part.
struct Divergence {
    Cause cause = Cause::none;
    int level = 0;  // depth, cutoff, secondary: the depth of the ray one side has and the other
                    // lacks or sees hit elsewhere (1: the first reflection); shadow: the node's
    int sample = 0; // the first sample (row-major) whose trees part
    int node_a = -1, node_b = -1; // there: the nodes (-1: the side has none)
};

// The first place, in DESIGN §13's order, where `a` and `b` part: sampling when their grids
// differ, else the first sample whose trees part, else precision. Call it for a pixel that
// differs; the trees themselves cannot say whether the bytes do. One side's trees may be
// traced only to one level below the other's deepest node (frame/difference.cpp says why the
// walk then finds what it finds on the whole trees).
Divergence first_divergence(const PixelTrees& a, const PixelTrees& b);

// The nodes of two trees laid side by side, in the walk's order: pairs of node indices, -1 where
// one side has no such node (it stopped, or hit nothing, or hit another object whose subtree
// is then that side's alone).
std::vector<std::pair<int, int>> align_trees(const SampleTree& a, const SampleTree& b);

// Traces pixels of one setting again in ray mode with the recorder on, in the precision of the
// tracer that made it, its World built once (ray_pixel_tracer below). A frame in double precision
// keeps one of these to give its pixels' trees.
class PixelTracer {
  public:
    virtual ~PixelTracer() = default;
    // The pixels' trees (row-major indices), as the render traces them. `refined`: adaptive
    // antialiasing's verdict per pixel of the frame (empty: none refined). `depths`: per pixel,
    // a maximum depth below the scene's to trace it to (empty: the scene's).
    virtual std::vector<PixelTrees> trees(std::span<const std::uint32_t> pixels,
                                          std::span<const std::uint8_t> refined,
                                          std::span<const int> depths) const = 0;
};

// A PixelTracer for `scene`, in the namespace's precision.
inline namespace f32 {
std::unique_ptr<PixelTracer> ray_pixel_tracer(const Scene& scene, std::optional<AccelKind> accel);
}
inline namespace f64 {
std::unique_ptr<PixelTracer> ray_pixel_tracer(const Scene& scene, std::optional<AccelKind> accel);
}

} // namespace glint
