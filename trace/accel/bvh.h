// Bounding volume hierarchy of axis-aligned boxes: binned SAH build (parallel at the top), flat
// node array, iterative nearest-child-first traversal.
#pragma once

#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <span>
#include <vector>

namespace glint {

struct BvhNode {
    Bounds bounds;
    std::uint32_t
        first; // leaf: first index into items; inner: index of the left child (right = +1)
    std::uint32_t count; // leaf: number of items; inner: 0
};

class Bvh {
  public:
    Bvh() = default;
    explicit Bvh(std::span<const Bounds> items);

    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<std::uint32_t>& items() const { return items_; }
    std::size_t memory_bytes() const { return nodes_.size() * sizeof(BvhNode) + items_.size() * 4; }
    std::size_t node_count() const { return nodes_.size(); }

    template <class Counters, class Visit>
    void traverse(const Ray& ray, float& t_max, Counters& counters, Visit&& visit) const {
        if (nodes_.empty()) return;
        const Vec3 inverse_direction = 1.0f / ray.direction;
        std::uint32_t stack[128]; // SAH trees over float boxes stay far shallower
        int top = 0;
        std::uint32_t node = 0;
        counters.node();
        if (entry_distance(nodes_[0].bounds, ray, inverse_direction, t_max) == kInfinity) return;
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
                float near = entry_distance(nodes_[n.first].bounds, ray, inverse_direction, t_max);
                float far =
                    entry_distance(nodes_[n.first + 1].bounds, ray, inverse_direction, t_max);
                std::uint32_t near_node = n.first, far_node = n.first + 1;
                if (far < near) std::swap(near, far), std::swap(near_node, far_node);
                if (near != kInfinity) {
                    if (far != kInfinity) stack[top++] = far_node; // may be pruned when popped
                    node = near_node;
                    continue;
                }
            }
            // Pop the next subtree still in reach of the current t_max.
            for (;;) {
                if (top == 0) return;
                node = stack[--top];
                counters.node();
                if (entry_distance(nodes_[node].bounds, ray, inverse_direction, t_max) != kInfinity)
                    break;
            }
        }
    }

  private:
    std::vector<BvhNode> nodes_;
    std::vector<std::uint32_t> items_;
};

} // namespace glint
