// Acceleration structures (docs/ARCHITECTURE.md, "Conventions"; Ray Tracing III: extents and space
// division), all behind one traversal: traverse(ray, t_max, counters, visit) calls visit(item,
// t_max) for the items the ray may hit, nearest regions first where the structure knows them; the
// visitor tests the item, may shorten t_max (closest hit) and returns true to stop (any hit). The
// kinds are a closed set: one switch dispatches, and each traversal is a template, so the hot path
// has no virtual call.
#pragma once

#include "trace/accel/accel_kind.h"
#include "trace/accel/binary_bvh.h"
#include "trace/accel/grid.h"
#include "trace/accel/kd_tree.h"
#include "trace/accel/sphere_tree.h"
#include "trace/accel/wide_bvh.h"

#include <optional>
#include <string_view>
#include <variant>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

// Brute force: every item's box, in order. The reference every other structure must match.
struct ItemList {
    std::vector<Bounds> bounds;

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        const SlabRay slab(ray);
        for (std::uint32_t i = 0; i < bounds.size(); ++i) {
            counters.node();
            if (!slab.hits(bounds[i], t_max)) continue;
            counters.primitive();
            if (visit(i, t_max)) return;
        }
    }
    std::size_t memory_bytes() const { return bounds.size() * sizeof(Bounds); }
    std::size_t node_count() const { return bounds.size(); }
};

class Accelerator {
  public:
    Accelerator() = default;
    // Builds the structure over the items' world-space bounds.
    Accelerator(AccelKind kind, std::vector<Bounds> items);

    // The same kind over the same items with new bounds (the camera moved): a BVH (either) keeps
    // its tree and refits its boxes, a list takes the new boxes, the others are built again.
    Accelerator refitted(std::vector<Bounds> items) const;

    AccelKind kind() const { return static_cast<AccelKind>(structure_.index()); }
    // The eight-wide BVH, which alone traverses packets of rays; null for the other kinds.
    const WideBvh* wide_bvh() const { return std::get_if<WideBvh>(&structure_); }
    // The list, whose packets World takes object by object; null for the other kinds.
    const ItemList* item_list() const { return std::get_if<ItemList>(&structure_); }
    std::size_t memory_bytes() const;
    std::size_t node_count() const;

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        switch (structure_.index()) {
        case 0:
            return std::get<0>(structure_).traverse(ray, t_max, counters, visit);
        case 1:
            return std::get<1>(structure_).traverse(ray, t_max, counters, visit);
        case 2:
            return std::get<2>(structure_).traverse(ray, t_max, counters, visit);
        case 3:
            return std::get<3>(structure_).traverse(ray, t_max, counters, visit);
        case 4:
            return std::get<4>(structure_).traverse(ray, t_max, counters, visit);
        case 5:
            return std::get<5>(structure_).traverse(ray, t_max, counters, visit);
        }
    }

  private:
    // In AccelKind's order.
    std::variant<ItemList, WideBvh, SphereTree, UniformGrid, KdTree, BinaryBvh> structure_;
};

} // namespace GLINT_PRECISION
} // namespace glint
