#include "trace/accel/kd_tree.h"

#include <algorithm>
#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {
namespace {

constexpr int kBins = 32;
constexpr std::size_t kMaxLeafSize = 4;
constexpr Real kTraversalCost = 1.0_r; // relative to one item test

struct Builder {
    std::span<const Bounds> bounds;
    std::vector<KdNode>& nodes;
    std::vector<std::uint32_t>& items;
    int max_depth;

    void leaf(std::uint32_t index, const std::vector<std::uint32_t>& ids) {
        nodes[index] = {0, static_cast<std::uint32_t>(items.size()),
                        static_cast<std::uint32_t>(ids.size()), 3};
        items.insert(items.end(), ids.begin(), ids.end());
    }

    void build(std::uint32_t index, const Bounds& box, std::vector<std::uint32_t> ids, int depth) {
        const std::size_t n = ids.size();
        if (n <= kMaxLeafSize || depth >= max_depth) return leaf(index, ids);
        // Binned SAH over candidate planes: N_below counts boxes starting below, N_above boxes
        // ending above; a leaf costs n item tests.
        const Real area = box.area();
        Real best_cost = static_cast<Real>(n);
        int best_axis = -1;
        Real best_split = 0;
        for (int a = 0; a < 3; ++a) {
            const Real lo = box.lo[a], extent = box.hi[a] - box.lo[a];
            if (!(extent > 0)) continue;
            std::size_t starts[kBins] = {}, ends[kBins] = {};
            for (std::uint32_t id : ids) {
                const Real s =
                    std::clamp((bounds[id].lo[a] - lo) / extent * kBins, 0.0_r, kBins - 1.0_r);
                const Real e =
                    std::clamp((bounds[id].hi[a] - lo) / extent * kBins, 0.0_r, kBins - 1.0_r);
                ++starts[static_cast<int>(s)];
                ++ends[static_cast<int>(e)];
            }
            std::size_t below = 0, above = n;
            for (int b = 1; b < kBins; ++b) {
                below += starts[b - 1];
                above -= ends[b - 1];
                const Real split = lo + extent * b / kBins;
                Bounds lower = box, upper = box;
                lower.hi[a] = split, upper.lo[a] = split;
                const Real cost =
                    kTraversalCost + (lower.area() * below + upper.area() * above) / area;
                if (cost < best_cost) best_cost = cost, best_axis = a, best_split = split;
            }
        }
        if (best_axis < 0) return leaf(index, ids);
        std::vector<std::uint32_t> below, above;
        for (std::uint32_t id : ids) {
            const Bounds& b = bounds[id];
            if (b.lo[best_axis] < best_split ||
                (b.lo[best_axis] == best_split && b.hi[best_axis] == best_split))
                below.push_back(id);
            if (b.hi[best_axis] > best_split) above.push_back(id);
        }
        if (below.size() == n && above.size() == n) return leaf(index, ids); // no separation at all
        ids.clear();
        ids.shrink_to_fit();
        const auto children = static_cast<std::uint32_t>(nodes.size());
        nodes.resize(nodes.size() + 2);
        nodes[index] = {best_split, children, 0, static_cast<std::uint8_t>(best_axis)};
        Bounds lower = box, upper = box;
        lower.hi[best_axis] = best_split, upper.lo[best_axis] = best_split;
        build(children, lower, std::move(below), depth + 1);
        build(children + 1, upper, std::move(above), depth + 1);
    }
};

} // namespace

KdTree::KdTree(std::span<const Bounds> item_bounds) {
    if (item_bounds.empty()) return;
    for (const Bounds& b : item_bounds) bounds_.extend(b);
    std::vector<std::uint32_t> ids(item_bounds.size());
    for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
    nodes_.resize(1);
    // pbrt's depth limit, 8 + 1.3·log2(n): deep enough for SAH, shallow enough for the stack.
    const int max_depth = std::min(
        100, static_cast<int>(std::lround(8 + 1.3 * std::log2(static_cast<double>(ids.size())))));
    Builder{item_bounds, nodes_, items_, max_depth}.build(0, bounds_, std::move(ids), 0);
}

} // namespace GLINT_PRECISION
} // namespace glint
