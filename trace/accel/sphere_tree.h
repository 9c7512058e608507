// Hierarchy of bounding spheres, the lecture's extents ("if (b² − 4ac) < 0 the ray misses the
// sphere: fast to compute"). Its topology is the BVH's (placing spheres automatically is, as
// the lecture says, a research problem); each node holds the sphere enclosing its children.
#pragma once

#include "trace/accel/binary_bvh.h"

#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {

struct BoundingSphere {
    Vec3 centre;
    Real radius;
};

class SphereTree {
  public:
    SphereTree() = default;
    explicit SphereTree(std::span<const Bounds> items);

    std::size_t memory_bytes() const {
        return topology_.memory_bytes() + spheres_.size() * sizeof(BoundingSphere);
    }
    std::size_t node_count() const { return spheres_.size(); }

    // Entry distance into a sphere over [0, t_max], or infinity.
    static Real entry_distance(const BoundingSphere& s, const Ray& ray, Real t_max) {
        const Vec3 oc = s.centre - ray.origin;
        const Real a = glm::dot(ray.direction, ray.direction);
        const Real b = glm::dot(oc, ray.direction);
        // Padded by a relative 1e-5 for the rounding of this test (|oc|² and b² carry ~1e-7).
        const Real r = s.radius * (1 + 1e-5_r) + 1e-5_r * std::sqrt(glm::dot(oc, oc));
        const Vec3 closest = oc - (b / a) * ray.direction; // cancellation-free, as for spheres
        const Real discriminant = a * (r * r - glm::dot(closest, closest));
        if (discriminant < 0) return kInfinity;
        const Real root = std::sqrt(discriminant);
        const Real t0 = (b - root) / a, t1 = (b + root) / a;
        if (t1 < 0 || t0 > t_max) return kInfinity;
        return std::max(t0, 0.0_r);
    }

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        const auto& nodes = topology_.nodes();
        if (nodes.empty()) return;
        std::uint32_t stack[kMaxBvhDepth]; // the BVH's topology, so its depth
        int top = 0;
        std::uint32_t node = 0;
        counters.node();
        if (entry_distance(spheres_[0], ray, t_max) == kInfinity) return;
        for (;;) {
            const BvhNode& n = nodes[node];
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    counters.primitive();
                    if (visit(topology_.items()[i], t_max)) return;
                }
            } else {
                counters.node();
                counters.node();
                Real near = entry_distance(spheres_[n.first], ray, t_max);
                Real far = entry_distance(spheres_[n.first + 1], ray, t_max);
                std::uint32_t near_node = n.first, far_node = n.first + 1;
                if (far < near) std::swap(near, far), std::swap(near_node, far_node);
                if (near != kInfinity) {
                    if (far != kInfinity) stack[top++] = far_node;
                    node = near_node;
                    continue;
                }
            }
            for (;;) {
                if (top == 0) return;
                node = stack[--top];
                counters.node();
                if (entry_distance(spheres_[node], ray, t_max) != kInfinity) break;
            }
        }
    }

  private:
    BinaryBvh topology_;
    std::vector<BoundingSphere> spheres_; // per node of topology_
};

} // namespace GLINT_PRECISION
} // namespace glint
