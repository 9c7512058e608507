// kd-tree (binary space partitioning with axis-aligned planes), built by the surface area
// heuristic; items straddling a plane go to both sides. Traversed front to back with a stack of
// ray segments (pbrt-v3's KdTreeAccel).
#pragma once

#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <span>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

struct KdNode {
    Real split;          // inner: plane position on `axis`
    std::uint32_t first; // inner: index of the below child (above = +1); leaf: first into items
    std::uint32_t count; // leaf: number of items
    std::uint8_t axis;   // 0, 1, 2; 3 for a leaf
};

class KdTree {
  public:
    KdTree() = default;
    explicit KdTree(std::span<const Bounds> items);

    std::size_t memory_bytes() const { return nodes_.size() * sizeof(KdNode) + items_.size() * 4; }
    std::size_t node_count() const { return nodes_.size(); }

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        if (nodes_.empty()) return;
        const SlabRay slab(ray);
        const Vec3& inverse_direction = slab.inverse_direction;
        Real t_min, t_end; // the ray's segment inside the root box
        if (!slab.clip(bounds_, t_max, t_min, t_end)) return;
        struct Segment {
            std::uint32_t node;
            Real t_min, t_max;
        } stack[128];
        int top = 0;
        std::uint32_t node = 0;
        // Whether a lies before b by more than rounding. Segment ends are plane crossings
        // computed in float, each off by a few ulps; far from the planes (a ray 1e15 long past
        // a leaf 0.3 across, found by fuzz_nff) the crossings of neighbouring planes round
        // together, and exact comparisons skipped the leaf of a sphere the list hits. So a
        // child is skipped, and a segment pruned, only when it is clearly beyond.
        const auto before = [](Real a, Real b) { return a * (1.0_r + 4.0_r * gamma(3)) < b; };
        for (;;) {
            if (before(t_max, t_min)) { // the best hit lies before this segment
                if (top == 0) return;
                const Segment s = stack[--top];
                node = s.node, t_min = s.t_min, t_end = s.t_max;
                continue;
            }
            counters.node();
            const KdNode& n = nodes_[node];
            if (n.axis == 3) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    counters.primitive();
                    if (visit(items_[i], t_max)) return;
                }
                if (top == 0) return;
                const Segment s = stack[--top];
                node = s.node, t_min = s.t_min, t_end = s.t_max;
                continue;
            }
            const int a = n.axis;
            const Real o = ray.origin[a], d = ray.direction[a];
            const bool below_first = o < n.split || (o == n.split && d <= 0);
            const std::uint32_t first = below_first ? n.first : n.first + 1;
            const std::uint32_t second = below_first ? n.first + 1 : n.first;
            if (d == 0) { // parallel to the plane: only the origin's side
                node = first;
                continue;
            }
            const Real t_plane = (n.split - o) * inverse_direction[a];
            if (before(t_end, t_plane) || t_plane <= 0) {
                node = first;
            } else if (before(t_plane, t_min)) {
                node = second;
            } else {
                stack[top++] = {second, t_plane, t_end};
                node = first;
                t_end = t_plane;
            }
        }
    }

  private:
    Bounds bounds_;
    std::vector<KdNode> nodes_;
    std::vector<std::uint32_t> items_;
};

} // namespace GLINT_PRECISION
} // namespace glint
