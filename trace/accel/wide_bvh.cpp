#include "trace/accel/wide_bvh.h"

#include <algorithm>
#include <cassert>

namespace glint {
inline namespace GLINT_PRECISION {
namespace {

void set_lane(WideBvhNode& node, int lane, const Bounds& box, std::uint32_t child,
              std::uint32_t count) {
    for (int a = 0; a < 3; ++a) node.box[a][0][lane] = box.lo[a], node.box[a][1][lane] = box.hi[a];
    node.child[lane] = child;
    node.count[lane] = static_cast<std::uint8_t>(count);
}

WideBvhNode empty_node() {
    WideBvhNode node{};
    for (int lane = 0; lane < kBvhWidth; ++lane) set_lane(node, lane, Bounds{}, kEmptyChild, 0);
    return node;
}

// The number of leaves below each binary node.
std::vector<std::uint32_t> leaf_counts(const BinaryBvh& tree) {
    const std::vector<BvhNode>& b = tree.nodes();
    std::vector<std::uint32_t> leaves(b.size(), 1);
    // A node's children follow it (BinaryBvh builds depth first), so one pass from the back sees
    // both children of a node before the node.
    for (std::size_t i = b.size(); i-- > 0;)
        if (b[i].count == 0) {
            assert(b[i].first > i);
            leaves[i] = leaves[b[i].first] + leaves[b[i].first + 1];
        }
    return leaves;
}

// Collapses the binary subtree under `binary` into wide node `index` and its descendants: the
// node's children are the binary node's two, each inner one replaced by its own two until there
// are eight or only leaves (the usual collapse, e.g. Wald et al. 2008, "Getting rid of packets").
// Which to open first: the largest by area among those with more than eight leaves below (too
// many for one node of their own), then the one with the fewest leaves (whose leaves would
// otherwise make a node of a few lanes): on the 10⁶-triangle terrain nodes hold 5.7 children on
// average instead of 4.4, and there are 28% fewer (bench/accel_bench.cpp, MeshBuild's label).
// Nodes are laid out depth first, so a subtree is contiguous.
void collapse(const BinaryBvh& tree, const std::vector<std::uint32_t>& leaves, std::uint32_t binary,
              std::uint32_t index, std::vector<WideBvhNode>& nodes) {
    const std::vector<BvhNode>& b = tree.nodes();
    std::uint32_t children[kBvhWidth] = {b[binary].first, b[binary].first + 1};
    int count = 2;
    const auto open_next = [&] {
        int widest = -1;
        for (int k = 0; k < count; ++k)
            if (b[children[k]].count == 0 && leaves[children[k]] > kBvhWidth &&
                (widest < 0 || b[children[k]].bounds.area() > b[children[widest]].bounds.area()))
                widest = k;
        if (widest >= 0) return widest;
        int fewest = -1;
        for (int k = 0; k < count; ++k)
            if (b[children[k]].count == 0 &&
                (fewest < 0 || leaves[children[k]] < leaves[children[fewest]]))
                fewest = k;
        return fewest;
    };
    while (count < kBvhWidth) {
        const int opened = open_next();
        if (opened < 0) break;
        const std::uint32_t node = children[opened];
        children[opened] = b[node].first;
        children[count++] = b[node].first + 1;
    }
    for (int k = 0; k < count; ++k) {
        const BvhNode& child = b[children[k]];
        if (child.count > 0) {
            set_lane(nodes[index], k, child.bounds, child.first, child.count);
        } else {
            const auto below = static_cast<std::uint32_t>(nodes.size());
            nodes.push_back(empty_node());
            set_lane(nodes[index], k, child.bounds, below, 0);
            collapse(tree, leaves, children[k], below, nodes);
        }
    }
}

// The box of every lane of node `index` over `items`, refitted below it first; their union.
Bounds refit(std::vector<WideBvhNode>& nodes, const std::vector<std::uint32_t>& order,
             std::span<const Bounds> items, std::uint32_t index) {
    Bounds all;
    for (int lane = 0; lane < kBvhWidth; ++lane) {
        WideBvhNode& node = nodes[index];
        const std::uint32_t child = node.child[lane], count = node.count[lane];
        if (child == kEmptyChild) continue;
        Bounds box;
        if (count > 0) {
            for (std::uint32_t slot = child; slot < child + count; ++slot)
                box.extend(items[order[slot]]);
        } else {
            box = refit(nodes, order, items, child);
        }
        set_lane(nodes[index], lane, box, child, count);
        all.extend(box);
    }
    return all;
}

// Moves every leaf's items to a first slot that is a multiple of `alignment`, in slot order,
// with kEmptyChild in the slots left between them.
void align_leaves(std::vector<WideBvhNode>& nodes, std::vector<std::uint32_t>& items,
                  std::uint32_t alignment) {
    std::vector<std::pair<std::uint32_t, std::uint32_t*>> leaves; // first slot, where it is kept
    for (WideBvhNode& node : nodes)
        for (int lane = 0; lane < kBvhWidth; ++lane)
            if (node.child[lane] != kEmptyChild && node.count[lane] > 0)
                leaves.emplace_back(node.child[lane], &node.child[lane]);
    std::sort(leaves.begin(), leaves.end());
    std::vector<std::uint32_t> aligned;
    aligned.reserve(items.size() + leaves.size() * (alignment - 1));
    for (std::size_t k = 0; k < leaves.size(); ++k) {
        const std::uint32_t first = leaves[k].first;
        const std::uint32_t end =
            k + 1 < leaves.size() ? leaves[k + 1].first : static_cast<std::uint32_t>(items.size());
        aligned.resize((aligned.size() + alignment - 1) / alignment * alignment, kEmptyChild);
        *leaves[k].second = static_cast<std::uint32_t>(aligned.size());
        aligned.insert(aligned.end(), items.begin() + first, items.begin() + end);
    }
    aligned.resize((aligned.size() + alignment - 1) / alignment * alignment, kEmptyChild);
    items = std::move(aligned);
}

} // namespace

WideBvh::WideBvh(std::span<const Bounds> item_bounds, LeafCosts costs) {
    if (item_bounds.empty()) return;
    const BinaryBvh tree(item_bounds, costs);
    items_ = tree.items();
    nodes_.push_back(empty_node());
    const BvhNode& root = tree.nodes()[0];
    if (root.count > 0) // few enough items for one leaf: a root with one child
        set_lane(nodes_[0], 0, root.bounds, root.first, root.count);
    else
        collapse(tree, leaf_counts(tree), 0, 0, nodes_);
    if (costs.block > 1) align_leaves(nodes_, items_, costs.block);
}

WideBvh WideBvh::refitted(std::span<const Bounds> items) const {
    WideBvh moved = *this;
    if (!moved.nodes_.empty()) refit(moved.nodes_, moved.items_, items, 0);
    return moved;
}

} // namespace GLINT_PRECISION
} // namespace glint
