// Bounding volume hierarchy of axis-aligned boxes: binned SAH build (parallel at the top), flat
// node array, iterative nearest-child-first traversal.
#pragma once

#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <span>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

struct BvhNode {
    Bounds bounds;
    std::uint32_t
        first; // leaf: first index into items; inner: index of the left child (right = +1)
    std::uint32_t count; // leaf: number of items; inner: 0
};

// Deepest a tree may be: traversal stacks (here and in sphere_tree.h) hold one entry a level.
// SAH alone does not bound depth (boxes at 2⁻⁵ᵏ along a line peel off one a level: 84 boxes
// made 73 levels, tests/accel_test.cpp), so the build switches to object-median splits below
// kSahDepth, which add at most log2(n) ≤ 32 levels.
inline constexpr int kMaxBvhDepth = 128;
inline constexpr int kSahDepth = 64;
static_assert(kSahDepth + 32 + 1 <= kMaxBvhDepth);

// What the SAH weighs a tree's leaves and levels by (BinaryBvh's and WideBvh's constructors).
struct LeafCosts {
    // Items a leaf tests together (a mesh's triangles, four to a SIMD block): the SAH counts a
    // leaf of n items as ⌈n / block⌉ tests, which favours full blocks, and a leaf of one block
    // is never split.
    std::uint32_t block = 1;
    // One more level, in those tests per unit of the node's area: a node is split only where
    // its children's expected tests save more than this.
    Real level = 0;
    // The most items a leaf holds, whatever the SAH says.
    std::uint32_t most = 8;
};

// A scene's objects, tested one at a time: the SAH decides every leaf, a level costing half an
// object's test. Forcing leaves of up to 4 objects, as a mesh's blocks are (the rule until
// round three), made 1080p ray frames 1.2–1.7× slower where long or overlapping objects share
// boxes (lattice-6, tree-11, rings-7, gears-4) and no scene measurably faster; without the
// level's cost, shells-2's nested spheres were split apart and 1.5× slower
// (docs/PERFORMANCE.md, "Object leaves chosen by the SAH").
inline constexpr LeafCosts kObjectLeaves{1, 0.5_r};

class BinaryBvh {
  public:
    BinaryBvh() = default;
    explicit BinaryBvh(std::span<const Bounds> items, LeafCosts costs = kObjectLeaves);

    // This tree over new boxes of the same items: each node's box the union of its items' or
    // children's. Conservative as a fresh build is; only the SAH's choice of splits may be worse.
    BinaryBvh refitted(std::span<const Bounds> items) const;

    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<std::uint32_t>& items() const { return items_; }
    std::size_t memory_bytes() const { return nodes_.size() * sizeof(BvhNode) + items_.size() * 4; }
    std::size_t node_count() const { return nodes_.size(); }

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        if (nodes_.empty()) return;
        const SlabRay slab(ray);
        struct Entry {
            std::uint32_t node;
            Real t;            // where the ray enters the node's box
        } stack[kMaxBvhDepth]; // one far child per level at most
        int top = 0;
        counters.node();
        Real t_root = slab.entry(nodes_[0].bounds, t_max);
        if (t_root == kInfinity) return;
        std::uint32_t node = 0;
        for (;;) {
            const BvhNode& n = nodes_[node];
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    counters.primitive();
                    if (visit(items_[i], t_max)) return;
                }
            } else {
                counters.node();
                counters.node();
                Real near = slab.entry(nodes_[n.first].bounds, t_max);
                Real far = slab.entry(nodes_[n.first + 1].bounds, t_max);
                std::uint32_t near_node = n.first, far_node = n.first + 1;
                if (far < near) std::swap(near, far), std::swap(near_node, far_node);
                if (near != kInfinity) {
                    if (far != kInfinity) stack[top++] = {far_node, far};
                    node = near_node;
                    continue;
                }
            }
            // The next pushed subtree the ray still reaches before the best hit so far.
            do {
                if (top == 0) return;
                --top;
            } while (stack[top].t > t_max);
            node = stack[top].node;
        }
    }

  private:
    std::vector<BvhNode> nodes_;
    std::vector<std::uint32_t> items_;
};

} // namespace GLINT_PRECISION
} // namespace glint
