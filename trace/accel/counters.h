// What a traversal did, counted only when asked (--stats): NoCounters compiles to nothing.
#pragma once

#include <cstdint>

namespace glint {

struct NoCounters {
    void node() {}
    void primitive() {}
};

struct TraversalCounters {
    // Nodes visited: boxes (bvh2), spheres, cells or kd nodes; an eight-wide node (bvh) counts
    // once for its eight boxes, and once per ray of a packet that tests it.
    std::uint64_t nodes = 0;
    std::uint64_t primitives = 0; // objects (or triangles) whose exact test ran

    void node() { ++nodes; }
    void primitive() { ++primitives; }
    TraversalCounters& operator+=(const TraversalCounters& o) {
        nodes += o.nodes, primitives += o.primitives;
        return *this;
    }
};

inline TraversalCounters operator+(TraversalCounters a, const TraversalCounters& b) {
    return a += b;
}

} // namespace glint
