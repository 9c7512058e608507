#include "trace/accel/sphere_tree.h"

namespace glint {
inline namespace GLINT_PRECISION {
namespace {

BoundingSphere around(const Bounds& b) {
    return {b.centre(), 0.5_r * glm::length(b.hi - b.lo)};
}

// The smallest sphere enclosing two spheres.
BoundingSphere merge(const BoundingSphere& a, const BoundingSphere& b) {
    const Real d = glm::length(b.centre - a.centre);
    if (d + b.radius <= a.radius) return a;
    if (d + a.radius <= b.radius) return b;
    const Real radius = 0.5_r * (d + a.radius + b.radius);
    return {a.centre + ((radius - a.radius) / d) * (b.centre - a.centre), radius * (1 + 1e-6_r)};
}

} // namespace

SphereTree::SphereTree(std::span<const Bounds> items) : topology_(items) {
    const auto& nodes = topology_.nodes();
    spheres_.resize(nodes.size());
    // Children always follow their parent in the node array, so a reverse sweep is bottom-up.
    for (std::size_t k = nodes.size(); k-- > 0;) {
        const BvhNode& n = nodes[k];
        if (n.count > 0) {
            BoundingSphere s = around(items[topology_.items()[n.first]]);
            for (std::uint32_t i = n.first + 1; i < n.first + n.count; ++i)
                s = merge(s, around(items[topology_.items()[i]]));
            spheres_[k] = s;
        } else {
            spheres_[k] = merge(spheres_[n.first], spheres_[n.first + 1]);
        }
    }
}

} // namespace GLINT_PRECISION
} // namespace glint
