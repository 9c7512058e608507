#include "trace/ray_tree.h"

#include <algorithm>

namespace glint {

namespace {

// Where a walk of two trees stands: the first divergence found, if any.
struct Walk {
    const SampleTree& a;
    const SampleTree& b;
    Divergence found;

    bool part(Cause cause, int level, int node_a, int node_b) {
        found.cause = cause, found.level = level, found.node_a = node_a, found.node_b = node_b;
        return true;
    }

    // A side that casts a ray the other does not: why the other stopped.
    static Cause stopped(Stop stop) {
        switch (stop) {
        case Stop::min_weight:
            return Cause::cutoff;
        case Stop::max_depth:
        case Stop::tree_budget: // the tree's ray budget: a limit on how far it goes, like depth
            return Cause::depth;
        case Stop::cast:
        case Stop::none:
            break;
        }
        return Cause::secondary; // cannot happen where both hit the same object
    }

    // Nodes i of a and j of b, which the walk reached by the same path: true where they part.
    bool walk(int i, int j) {
        const TreeNode& x = a[static_cast<std::size_t>(i)];
        const TreeNode& y = b[static_cast<std::size_t>(j)];
        if (x.object != y.object)
            return part(x.kind == RayKind::primary ? Cause::primary : Cause::secondary, x.depth, i,
                        j);
        if (x.object == kNoObject) return false;
        if (x.lights != y.lights) return part(Cause::shadow, x.depth, i, j);
        for (std::size_t k = 0; k < 2; ++k) {
            const bool cast_a = x.stop[k] == Stop::cast, cast_b = y.stop[k] == Stop::cast;
            if (cast_a && cast_b) {
                if (walk(x.child[k], y.child[k])) return true;
            } else if (cast_a != cast_b) {
                return part(stopped(cast_a ? y.stop[k] : x.stop[k]), x.depth + 1,
                            cast_a ? x.child[k] : -1, cast_b ? y.child[k] : -1);
            }
        }
        return false;
    }
};

} // namespace

int deepest(const PixelTrees& trees) {
    int depth = 0;
    for (const SampleTree& tree : trees.samples)
        for (const TreeNode& node : tree) depth = std::max(depth, node.depth);
    return depth;
}

Divergence first_divergence(const PixelTrees& a, const PixelTrees& b) {
    if (a.grid != b.grid || a.samples.size() != b.samples.size())
        return {Cause::sampling, 0, 0, -1, -1};
    for (std::size_t s = 0; s < a.samples.size(); ++s) {
        Walk walk{a.samples[s], b.samples[s], {}};
        if (walk.walk(0, 0)) {
            walk.found.sample = static_cast<int>(s);
            return walk.found;
        }
    }
    return {Cause::precision, 0, 0, -1, -1};
}

namespace {

void align(const SampleTree& a, const SampleTree& b, int i, int j,
           std::vector<std::pair<int, int>>& out) {
    out.emplace_back(i, j);
    const bool same =
        i >= 0 && j >= 0 &&
        a[static_cast<std::size_t>(i)].object == b[static_cast<std::size_t>(j)].object;
    for (std::size_t k = 0; k < 2; ++k) {
        const int ci = i >= 0 ? a[static_cast<std::size_t>(i)].child[k] : -1;
        const int cj = j >= 0 ? b[static_cast<std::size_t>(j)].child[k] : -1;
        if (same) {
            if (ci >= 0 || cj >= 0) align(a, b, ci, cj, out);
        } else { // another object on each side: each subtree is its side's alone
            if (ci >= 0) align(a, b, ci, -1, out);
            if (cj >= 0) align(a, b, -1, cj, out);
        }
    }
}

} // namespace

std::vector<std::pair<int, int>> align_trees(const SampleTree& a, const SampleTree& b) {
    std::vector<std::pair<int, int>> out;
    if (!a.empty() || !b.empty()) align(a, b, a.empty() ? -1 : 0, b.empty() ? -1 : 0, out);
    return out;
}

} // namespace glint
