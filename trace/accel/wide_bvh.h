// Four-wide bounding volume hierarchy: the binary SAH tree (binary_bvh.h) collapsed so that each
// node holds the boxes of up to four children side by side, tested together with one SIMD slab
// test (SSE in float, which every x86-64 processor has; the same arithmetic lane by lane in
// double). Leaves are the binary tree's: their items are contiguous, so that a user may keep its
// hot data (a mesh's triangles) in leaf order and read it by slot (traverse_leaves).
#pragma once

#include "trace/accel/binary_bvh.h"
#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <cassert>
#include <span>
#include <vector>

#if defined(__SSE2__) && !GLINT_DOUBLE
#include <immintrin.h>
#define GLINT_WIDE_BVH_SSE 1
#else
#define GLINT_WIDE_BVH_SSE 0
#endif

namespace glint {
inline namespace GLINT_PRECISION {

inline constexpr int kBvhWidth = 4;
inline constexpr std::uint32_t kEmptyChild = ~0u;
inline constexpr int kMaxPacket = 16; // rays a packet traversal takes at once

// 128 bytes in float (two cache lines): the six planes of four boxes, then the children.
struct alignas(64) WideBvhNode {
    // box[axis][0] holds the children's low ends along axis, box[axis][1] their high ends, one
    // lane per child. An empty lane is lo = +inf, hi = −inf: a ray enters it at +inf and leaves
    // at −inf, so the slab test rejects it with no separate check.
    Real box[3][2][kBvhWidth];
    std::uint32_t child[kBvhWidth]; // inner: the child's node index; leaf: its first item slot
    std::uint8_t count[kBvhWidth];  // leaf: its number of items; inner child or empty lane: 0
};

// A ray prepared for wide nodes: SlabRay's reciprocals (±1e30 for axis-parallel directions),
// and per axis which plane it enters by (the low one where the direction is positive), so that
// each axis costs two subtractions and two multiplications for all four children, no min/max.
// For boxes with lo ≤ hi this is SlabRay::clip exactly, enlargement of the far end included.
struct WideRay {
    Vec3 origin{0};
    Vec3 inverse_direction{0};
    int near[3] = {}; // 0: the low plane is entered first; 1: the high one

    WideRay() = default;
    explicit WideRay(const Ray& ray) {
        const SlabRay slab(ray);
        origin = slab.origin, inverse_direction = slab.inverse_direction;
        for (int a = 0; a < 3; ++a) near[a] = std::signbit(inverse_direction[a]) ? 1 : 0;
    }

    // Bit k set when the ray meets child k's box within [0, t_max]; t_near[k] where it enters.
    [[gnu::always_inline]] unsigned enter(const WideBvhNode& n, Real t_max,
                                          Real (&t_near)[kBvhWidth]) const {
        constexpr Real widen = 1.0_r + 2.0_r * gamma(3); // SlabRay::clip's enlargement
#if GLINT_WIDE_BVH_SSE
        __m128 t_in = _mm_setzero_ps(), t_out = _mm_set1_ps(kInfinity);
        for (int a = 0; a < 3; ++a) {
            const __m128 o = _mm_set1_ps(origin[a]), inv = _mm_set1_ps(inverse_direction[a]);
            const __m128 in = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[a][near[a]]), o), inv);
            const __m128 out = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[a][1 - near[a]]), o), inv);
            t_in = _mm_max_ps(t_in, in);
            t_out = _mm_min_ps(t_out, out);
        }
        t_out = _mm_min_ps(_mm_mul_ps(t_out, _mm_set1_ps(widen)), _mm_set1_ps(t_max));
        _mm_storeu_ps(t_near, t_in);
        return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(t_in, t_out)));
#else
        unsigned mask = 0;
        for (int k = 0; k < kBvhWidth; ++k) {
            Real t_in = 0, t_out = kInfinity;
            for (int a = 0; a < 3; ++a) {
                const Real in = (n.box[a][near[a]][k] - origin[a]) * inverse_direction[a];
                const Real out = (n.box[a][1 - near[a]][k] - origin[a]) * inverse_direction[a];
                t_in = std::max(t_in, in), t_out = std::min(t_out, out);
            }
            t_out = std::min(t_out * widen, t_max);
            t_near[k] = t_in;
            mask |= unsigned(t_in <= t_out) << k;
        }
        return mask;
#endif
    }
};

class WideBvh {
  public:
    WideBvh() = default;
    explicit WideBvh(std::span<const Bounds> items);

    // This tree over new boxes of the same items (BinaryBvh::refitted's contract).
    WideBvh refitted(std::span<const Bounds> items) const;

    const std::vector<WideBvhNode>& nodes() const { return nodes_; }
    // Item slot → item: leaves name ranges of slots.
    const std::vector<std::uint32_t>& items() const { return items_; }
    std::size_t memory_bytes() const {
        return nodes_.size() * sizeof(WideBvhNode) + items_.size() * 4;
    }
    std::size_t node_count() const { return nodes_.size(); }

    // The leaves the ray may meet, nearest box first: visit(first_slot, end_slot, t_max) may
    // shorten t_max and returns true to stop. Counts one node per wide node whose boxes it tests.
    template <class Counters, class VisitLeaf>
    void traverse_leaves(const Ray& ray, Real& t_max, Counters& counters, VisitLeaf&& visit) const {
        if (nodes_.empty()) return;
        const WideRay wide(ray);
        struct Entry {
            std::uint32_t child, count;
            Real t; // where the ray enters the child's box
        };
        // At most three children a level wait on the stack; the depth is the binary tree's.
        Entry stack[(kBvhWidth - 1) * kMaxBvhDepth + 1];
        int top = 0;
        std::uint32_t node = 0;
        for (;;) {
            counters.node();
            const WideBvhNode& n = nodes_[node];
            Real t_near[kBvhWidth];
            unsigned mask = wide.enter(n, t_max, t_near);
            // The children the ray meets, nearest first (insertion into at most four).
            Entry hit[kBvhWidth];
            int hits = 0;
            for (; mask != 0; mask &= mask - 1) {
                const int k = __builtin_ctz(mask);
                const Entry e{n.child[k], n.count[k], t_near[k]};
                int at = hits++;
                for (; at > 0 && hit[at - 1].t > e.t; --at) hit[at] = hit[at - 1];
                hit[at] = e;
            }
            for (int k = hits - 1; k > 0; --k) stack[top++] = hit[k];
            Entry next;
            if (hits > 0) {
                next = hit[0];
            } else if (!pop(stack, top, t_max, next)) {
                return;
            }
            // Leaves in order until the next inner node.
            while (next.count > 0) {
                if (visit(next.child, next.child + next.count, t_max)) return;
                if (!pop(stack, top, t_max, next)) return;
            }
            node = next.child;
        }
    }

    // The acceleration-structure contract (accel.h): visit(item, t_max) for every item of the
    // leaves the ray may meet.
    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        traverse_leaves(ray, t_max, counters,
                        [&](std::uint32_t begin, std::uint32_t end, Real& limit) {
                            for (std::uint32_t slot = begin; slot < end; ++slot) {
                                counters.primitive();
                                if (visit(items_[slot], limit)) return true;
                            }
                            return false;
                        });
    }

    // Packet traversal for up to kMaxPacket coherent rays (a tile's camera rays, or its shadow
    // rays towards one light): each node is fetched once for all the rays that reach it, and
    // tested against each of them with the single-ray test, so every ray is offered exactly the
    // leaves its own traversal could offer (in another order; the visitors' answers do not depend
    // on the order: tests/accel_test.cpp). visit(ray, first_slot, end_slot, t_max[ray]) may
    // shorten that ray's limit and returns true when the ray is done (any hit found).
    template <class Counters, class VisitLeaf>
    void traverse_packet(const WideRay* rays, int count, Real* t_max, Counters& counters,
                         VisitLeaf&& visit) const {
        assert(count <= kMaxPacket);
        if (nodes_.empty() || count == 0) return;
        using Mask = std::uint32_t;
        static_assert(kMaxPacket <= 8 * sizeof(Mask));
        struct Entry {
            std::uint32_t child, count;
            Mask rays; // the rays that met the child's box
            Real t;    // the nearest of their entry distances: the order children are taken in
        };
        Entry stack[(kBvhWidth - 1) * kMaxBvhDepth + 1];
        int top = 0;
        Mask done = 0; // rays whose visitor said they are finished
        Entry next{0, 0, count == 32 ? ~Mask{0} : (Mask{1} << count) - 1, 0};
        for (;;) {
            if (next.count == 0) { // an inner node: which of its children each ray meets
                const WideBvhNode& n = nodes_[next.child];
                Entry child[kBvhWidth];
                for (int k = 0; k < kBvhWidth; ++k)
                    child[k] = {n.child[k], n.count[k], 0, kInfinity};
                for (Mask active = next.rays & ~done; active != 0; active &= active - 1) {
                    const int r = __builtin_ctz(active);
                    counters.node();
                    Real t_near[kBvhWidth];
                    for (unsigned m = rays[r].enter(n, t_max[r], t_near); m != 0; m &= m - 1) {
                        const int k = __builtin_ctz(m);
                        child[k].rays |= Mask{1} << r;
                        child[k].t = std::min(child[k].t, t_near[k]);
                    }
                }
                // Nearest first: the others wait on the stack, farthest deepest.
                int hits = 0;
                for (int k = 0; k < kBvhWidth; ++k) {
                    if (child[k].rays == 0) continue;
                    const Entry e = child[k];
                    int at = hits++;
                    for (; at > 0 && child[at - 1].t > e.t; --at) child[at] = child[at - 1];
                    child[at] = e;
                }
                for (int k = hits - 1; k > 0; --k) stack[top++] = child[k];
                if (hits > 0) {
                    next = child[0];
                    continue;
                }
            } else { // a leaf: each ray that met its box visits it
                for (Mask active = next.rays & ~done; active != 0; active &= active - 1) {
                    const int r = __builtin_ctz(active);
                    if (visit(r, next.child, next.child + next.count, t_max[r]))
                        done |= Mask{1} << r;
                }
            }
            do {
                if (top == 0) return;
                next = stack[--top];
            } while ((next.rays & ~done) == 0);
        }
    }

  private:
    // The next waiting child the ray still reaches before t_max, if any.
    template <class Entry> static bool pop(const Entry* stack, int& top, Real t_max, Entry& next) {
        do {
            if (top == 0) return false;
            next = stack[--top];
        } while (next.t > t_max);
        return true;
    }

    std::vector<WideBvhNode> nodes_;
    std::vector<std::uint32_t> items_;
};

} // namespace GLINT_PRECISION
} // namespace glint
