#include "trace/accel/binary_bvh.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>

namespace glint {
inline namespace GLINT_PRECISION {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kParallelBelow = 4096; // subtrees smaller than this are built serially

struct Builder {
    std::span<const Bounds> bounds;
    LeafCosts costs;
    std::vector<Vec3> centres;
    std::vector<std::uint32_t>& items;
    std::vector<BvhNode>& nodes;
    std::atomic<std::uint32_t> next_node{1};

    // What the SAH counts a leaf of n items as: its blocks.
    Real tests(std::uint32_t n) const {
        return static_cast<Real>((n + costs.block - 1) / costs.block);
    }

    void leaf(BvhNode& node, std::uint32_t begin, std::uint32_t end) {
        node.first = begin;
        node.count = end - begin;
    }

    // Builds the subtree of items[begin, end) into nodes[index], `depth` levels below the root.
    // The binning, the choice of split and the partition stay in one body: they share the bin
    // arrays.
    void build(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int depth) {
        BvhNode& node = nodes[index];
        Bounds box, centroid_box;
        for (std::uint32_t i = begin; i < end; ++i) {
            box.extend(bounds[items[i]]);
            centroid_box.extend(centres[items[i]]);
        }
        node.bounds = box;
        const std::uint32_t count = end - begin;
        if (count <= costs.block) return leaf(node, begin, end);
        if (depth >= kSahDepth) return median_split(index, begin, end, depth, centroid_box);

        // Binned SAH over the centroids (Wald 2007): cost of a split ∝ A_left·N_left +
        // A_right·N_right, N counted in blocks (tests()).
        const Vec3 extent = centroid_box.hi - centroid_box.lo;
        Real best_cost = kInfinity;
        int best_axis = -1, best_split = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0)) continue;
            Bounds bin_box[kBins];
            std::uint32_t bin_count[kBins] = {};
            const Real scale = kBins / extent[axis];
            for (std::uint32_t i = begin; i < end; ++i) {
                const int b =
                    bin_index((centres[items[i]][axis] - centroid_box.lo[axis]) * scale, kBins);
                ++bin_count[b];
                bin_box[b].extend(bounds[items[i]]);
            }
            Real right_area[kBins];
            std::uint32_t right_count[kBins];
            Bounds right;
            std::uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.extend(bin_box[b]);
                n += bin_count[b];
                right_area[b] = right.area();
                right_count[b] = n;
            }
            Bounds left;
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                left.extend(bin_box[b]);
                n += bin_count[b];
                if (n == 0 || right_count[b + 1] == 0) continue;
                const Real cost =
                    left.area() * tests(n) + right_area[b + 1] * tests(right_count[b + 1]);
                if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = b;
            }
        }
        // A leaf costs one test per block; a split its children's expected tests and the level.
        const Real leaf_cost = box.area() * tests(count);
        if (count <= costs.most &&
            (best_axis < 0 || best_cost + costs.level * box.area() >= leaf_cost))
            return leaf(node, begin, end);
        std::uint32_t middle;
        if (best_axis >= 0) {
            const Real scale = kBins / extent[best_axis];
            const Real lo = centroid_box.lo[best_axis];
            middle = static_cast<std::uint32_t>(
                std::partition(items.begin() + begin, items.begin() + end,
                               [&](std::uint32_t item) {
                                   return bin_index((centres[item][best_axis] - lo) * scale,
                                                    kBins) <= best_split;
                               }) -
                items.begin());
        } else { // all centroids coincide: split the list in half
            middle = begin + count / 2;
        }
        if (middle == begin || middle == end) middle = begin + count / 2;
        split(index, begin, middle, end, depth);
    }

    void split(std::uint32_t index, std::uint32_t begin, std::uint32_t middle, std::uint32_t end,
               int depth) {
        const std::uint32_t children = next_node.fetch_add(2);
        nodes[index].first = children;
        nodes[index].count = 0;
        if (end - begin > kParallelBelow)
            tbb::parallel_invoke([&] { build(children, begin, middle, depth + 1); },
                                 [&] { build(children + 1, middle, end, depth + 1); });
        else
            build(children, begin, middle, depth + 1), build(children + 1, middle, end, depth + 1);
    }

    // Halves the items by count along the centroids' widest axis: depth grows by log2(n) at most.
    void median_split(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int depth,
                      const Bounds& centroid_box) {
        const Vec3 extent = centroid_box.hi - centroid_box.lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const std::uint32_t middle = begin + (end - begin) / 2;
        std::nth_element(
            items.begin() + begin, items.begin() + middle, items.begin() + end,
            [&](std::uint32_t a, std::uint32_t b) { return centres[a][axis] < centres[b][axis]; });
        split(index, begin, middle, end, depth);
    }
};

// The box of node `index` over `items`, refitted below it first.
Bounds refit(std::vector<BvhNode>& nodes, const std::vector<std::uint32_t>& order,
             std::span<const Bounds> items, std::uint32_t index) {
    BvhNode& node = nodes[index];
    Bounds box;
    if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
            box.extend(items[order[i]]);
    } else {
        box.extend(refit(nodes, order, items, node.first));
        box.extend(refit(nodes, order, items, node.first + 1));
    }
    node.bounds = box;
    return box;
}

} // namespace

BinaryBvh BinaryBvh::refitted(std::span<const Bounds> items) const {
    BinaryBvh moved = *this;
    if (!moved.nodes_.empty()) refit(moved.nodes_, moved.items_, items, 0);
    return moved;
}

BinaryBvh::BinaryBvh(std::span<const Bounds> item_bounds, LeafCosts costs) {
    if (item_bounds.empty()) return;
    items_.resize(item_bounds.size());
    for (std::uint32_t i = 0; i < items_.size(); ++i) items_[i] = i;
    nodes_.resize(2 * item_bounds.size()); // a binary tree with n leaves at most has 2n − 1 nodes
    Builder builder{item_bounds, costs, {}, items_, nodes_};
    builder.centres.reserve(item_bounds.size());
    for (const Bounds& b : item_bounds) builder.centres.push_back(b.centre());
    builder.build(0, 0, static_cast<std::uint32_t>(item_bounds.size()), 0);
    nodes_.resize(builder.next_node.load());

    // The parallel build allocates nodes in whatever order its tasks ran; a traversal touches
    // a path from the root, so lay every subtree out contiguously, depth first (children pairs
    // stay adjacent), which also makes the layout independent of thread timing.
    std::vector<BvhNode> ordered;
    ordered.reserve(nodes_.size());
    ordered.push_back(nodes_[0]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pending{{0, 0}}; // (old index, new index)
    while (!pending.empty()) {
        const auto [old_index, new_index] = pending.back();
        pending.pop_back();
        const BvhNode& n = nodes_[old_index];
        if (n.count > 0) continue;
        const auto children = static_cast<std::uint32_t>(ordered.size());
        ordered.push_back(nodes_[n.first]);
        ordered.push_back(nodes_[n.first + 1]);
        ordered[new_index].first = children;
        pending.push_back({n.first + 1, children + 1}); // the left subtree is laid out first
        pending.push_back({n.first, children});
    }
    nodes_ = std::move(ordered);
}

} // namespace GLINT_PRECISION
} // namespace glint
