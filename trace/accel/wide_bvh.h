// Eight-wide bounding volume hierarchy: the binary SAH tree (binary_bvh.h) collapsed so that
// each node holds the boxes of up to eight children side by side, tested together by one SIMD
// slab test: AVX2 where the processor has it, else two SSE halves (every x86-64 processor has
// SSE), the kernel chosen at start-up (trace/kernel.h); the same arithmetic lane by lane in
// double. Leaves are the binary tree's (at most 8 items): their items are contiguous, so that a
// user may keep its hot data (a mesh's triangles) in leaf order and read it by slot
// (traverse_leaves). Packets of up to kMaxPacket rays traverse it together (traverse_packet).
#pragma once

#include "trace/accel/binary_bvh.h"
#include "trace/accel/counters.h"
#include "trace/bounds.h"
#include "trace/kernel.h"

#include <cassert>
#include <span>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

inline constexpr int kBvhWidth = 8;
inline constexpr std::uint32_t kEmptyChild = ~0u;
inline constexpr int kMaxPacket = 16; // rays a packet traversal takes at once

// 256 bytes in float (four cache lines): the six planes of eight boxes, then the children.
struct alignas(64) WideBvhNode {
    // box[axis][0] holds the children's low ends along axis, box[axis][1] their high ends, one
    // lane per child. An empty lane is lo = +inf, hi = −inf: a ray enters it at +inf and leaves
    // at −inf, so the slab test rejects it with no separate check.
    Real box[3][2][kBvhWidth];
    std::uint32_t child[kBvhWidth]; // inner: the child's node index; leaf: its first item slot
    std::uint8_t count[kBvhWidth];  // leaf: its number of items; inner child or empty lane: 0
};

// Asks for every cache line of [p, p + bytes) to be fetched.
inline void prefetch_bytes(const void* p, std::size_t bytes) {
    const auto first = reinterpret_cast<std::uintptr_t>(p) & ~std::uintptr_t{63};
    const auto last = reinterpret_cast<std::uintptr_t>(p) + bytes - 1;
    for (std::uintptr_t line = first; line <= last; line += 64)
        __builtin_prefetch(reinterpret_cast<const void*>(line));
}

// SlabRay::clip's enlargement of the far end.
inline constexpr Real kSlabWiden = 1.0_r + 2.0_r * gamma(3);

struct WideRay;
struct PacketRays;
#if GLINT_SIMD
// The AVX2 kernel (defined below): WideRay::enter_sse's and PacketRays::enter_sse's operations,
// in the same order, eight lanes an instruction. Only functions marked for AVX2 are compiled
// for it (these, and the traversals that inline them: WideBvh's *_avx2), so that nothing they
// share with the rest of the program (an inline function of a header) is: the program still
// runs on a processor without AVX2, which never calls them (trace/kernel.h). No FMA: a
// multiply and an add are rounded apart, as in the other kernels.
[[gnu::target("avx2")]] inline unsigned enter_avx2(const WideRay& ray, const WideBvhNode& n,
                                                   Real t_max, Real (&t_near)[kBvhWidth]);
[[gnu::target("avx2")]] inline std::uint32_t
enter_avx2(const PacketRays& packet, const WideBvhNode& n, int k, std::uint32_t active, Real& t);
// The AVX-512 kernel, for packets only (a single ray's node test is eight lanes, AVX2's): the
// same operations sixteen rays an instruction, under the same rule for what it may share.
[[gnu::target("avx512f")]] inline std::uint32_t
enter_avx512(const PacketRays& packet, const WideBvhNode& n, int k, std::uint32_t active, Real& t);
#endif

// A ray prepared for wide nodes: SlabRay's reciprocals (±1e30 for axis-parallel directions),
// and per axis which plane it enters by (the low one where the direction is positive), so that
// each axis costs two subtractions and two multiplications for all children, no min/max.
// For boxes with lo ≤ hi this is SlabRay::clip exactly, enlargement of the far end included.
struct WideRay {
    Vec3 origin;
    Vec3 inverse_direction;
    int near[3]; // 0: the low plane is entered first; 1: the high one

    // Component by component, not through a SlabRay copied whole: that copy read eight bytes
    // that two four-byte stores had just written, a load the store buffer could not forward
    // here (perf annotate: 11% of balls-4's single shadow rays; docs/PERFORMANCE.md).
    explicit WideRay(const Ray& ray) {
        for (int a = 0; a < 3; ++a) {
            origin[a] = ray.origin[a];
            inverse_direction[a] = SlabRay::reciprocal(ray.direction[a]);
            near[a] = std::signbit(inverse_direction[a]) ? 1 : 0;
        }
    }

    // Bit k set when the ray meets child k's box within [0, t_max]; t_near[k] where it enters.
    // The portable kernel: two halves of four lanes (SSE), or lane by lane; enter_avx2 is the
    // same with eight.
    [[gnu::always_inline]] unsigned enter_sse(const WideBvhNode& n, Real t_max,
                                              Real (&t_near)[kBvhWidth]) const {
#if GLINT_SIMD
        unsigned mask = 0;
        for (int h = 0; h < kBvhWidth; h += 4) {
            __m128 t_in = _mm_setzero_ps(), t_out = _mm_set1_ps(kInfinity);
            for (int a = 0; a < 3; ++a) {
                const __m128 o = _mm_set1_ps(origin[a]), inv = _mm_set1_ps(inverse_direction[a]);
                const __m128 in =
                    _mm_mul_ps(_mm_sub_ps(_mm_load_ps(&n.box[a][near[a]][h]), o), inv);
                const __m128 out =
                    _mm_mul_ps(_mm_sub_ps(_mm_load_ps(&n.box[a][1 - near[a]][h]), o), inv);
                t_in = _mm_max_ps(t_in, in);
                t_out = _mm_min_ps(t_out, out);
            }
            t_out = _mm_min_ps(_mm_mul_ps(t_out, _mm_set1_ps(kSlabWiden)), _mm_set1_ps(t_max));
            _mm_storeu_ps(&t_near[h], t_in);
            mask |= static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(t_in, t_out))) << h;
        }
        return mask;
#else
        unsigned mask = 0;
        for (int k = 0; k < kBvhWidth; ++k) {
            Real t_in = 0, t_out = kInfinity;
            for (int a = 0; a < 3; ++a) {
                const Real in = (n.box[a][near[a]][k] - origin[a]) * inverse_direction[a];
                const Real out = (n.box[a][1 - near[a]][k] - origin[a]) * inverse_direction[a];
                t_in = std::max(t_in, in), t_out = std::min(t_out, out);
            }
            t_out = std::min(t_out * kSlabWiden, t_max);
            t_near[k] = t_in;
            mask |= unsigned(t_in <= t_out) << k;
        }
        return mask;
#endif
    }
};

// Up to kMaxPacket rays prepared for wide nodes, one lane per ray (structure of arrays), so that
// a child's box is tested against four rays per SSE instruction (eight with AVX2, sixteen with
// AVX-512). Lanes beyond the packet have t_max = −inf: no box is entered before it.
struct PacketRays {
    using Mask = std::uint32_t; // bit r: ray r
    static_assert(kMaxPacket <= 32 && kMaxPacket % 8 == 0);

    alignas(64) Real origin[3][kMaxPacket];
    alignas(64) Real inverse_direction[3][kMaxPacket];
    alignas(64) Real t_max[kMaxPacket];
    Mask all;

    PacketRays(const Ray* rays, int count, const Real* limits)
        : all(count == 32 ? ~Mask{0} : (Mask{1} << count) - 1) {
        for (int r = 0; r < kMaxPacket; ++r) {
            const Ray& ray = r < count ? rays[r] : Ray{Vec3(0), Vec3(1)};
            for (int a = 0; a < 3; ++a) // SlabRay's, component by component (WideRay's reason)
                origin[a][r] = ray.origin[a],
                inverse_direction[a][r] = SlabRay::reciprocal(ray.direction[a]);
            t_max[r] = r < count ? limits[r] : -kInfinity;
        }
    }

    // The rays whose t_max is at least t: those a child waiting with entry distance t (the
    // nearest of its rays') may still serve. A ray left out enters that child's box, and every
    // box in it, beyond its t_max: alone, it would have dropped it from its stack (pop).
    Mask reaching(Real t) const {
        Mask m = 0;
#if GLINT_SIMD
        const __m128 at = _mm_set1_ps(t);
        for (int g = 0; g < kMaxPacket; g += 4)
            m |= static_cast<Mask>(_mm_movemask_ps(_mm_cmpge_ps(_mm_load_ps(&t_max[g]), at))) << g;
#else
        for (int r = 0; r < kMaxPacket; ++r) m |= Mask{t_max[r] >= t} << r;
#endif
        return m;
    }

    // The rays of `active` that meet child k's box within [0, t_max]; `t` lowered to the
    // nearest of their entry distances. Per ray, SlabRay::clip's arithmetic: near and far of
    // each axis by min and max, which for a box with lo ≤ hi is the plane the sign selects.
    // The portable kernel: four rays at a time (SSE), or one; enter_avx2 is the same with eight.
    [[gnu::always_inline]] Mask enter_sse(const WideBvhNode& n, int k, Mask active, Real& t) const {
        Mask met = 0;
        for (int g = 0; g < kMaxPacket; g += 4) {
            if (((active >> g) & 15) == 0) continue;
#if GLINT_SIMD
            __m128 t_in = _mm_setzero_ps(), t_out = _mm_set1_ps(kInfinity);
            for (int a = 0; a < 3; ++a) {
                const __m128 o = _mm_load_ps(&origin[a][g]);
                const __m128 inv = _mm_load_ps(&inverse_direction[a][g]);
                const __m128 t0 = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(n.box[a][0][k]), o), inv);
                const __m128 t1 = _mm_mul_ps(_mm_sub_ps(_mm_set1_ps(n.box[a][1][k]), o), inv);
                t_in = _mm_max_ps(t_in, _mm_min_ps(t0, t1));
                t_out = _mm_min_ps(t_out, _mm_max_ps(t0, t1));
            }
            t_out = _mm_min_ps(_mm_mul_ps(t_out, _mm_set1_ps(kSlabWiden)), _mm_load_ps(&t_max[g]));
            const __m128 inside = _mm_cmple_ps(t_in, t_out);
            const Mask lanes = static_cast<Mask>(_mm_movemask_ps(inside)) & (active >> g) & 15;
            if (lanes == 0) continue;
            met |= lanes << g;
            alignas(16) Real entry[4];
            _mm_store_ps(entry, t_in);
            for (Mask l = lanes; l != 0; l &= l - 1) t = std::min(t, entry[__builtin_ctz(l)]);
#else
            for (int r = g; r < g + 4; ++r) {
                if (!((active >> r) & 1)) continue;
                Real t_in = 0, t_out = kInfinity;
                for (int a = 0; a < 3; ++a) {
                    const Real t0 = (n.box[a][0][k] - origin[a][r]) * inverse_direction[a][r];
                    const Real t1 = (n.box[a][1][k] - origin[a][r]) * inverse_direction[a][r];
                    t_in = std::max(t_in, std::min(t0, t1));
                    t_out = std::min(t_out, std::max(t0, t1));
                }
                if (t_in <= std::min(t_out * kSlabWiden, t_max[r]))
                    met |= Mask{1} << r, t = std::min(t, t_in);
            }
#endif
        }
        return met;
    }
};

#if GLINT_SIMD
[[gnu::target("avx2")]] inline unsigned enter_avx2(const WideRay& ray, const WideBvhNode& n,
                                                   Real t_max, Real (&t_near)[kBvhWidth]) {
    static_assert(kBvhWidth == 8);
    __m256 t_in = _mm256_setzero_ps(), t_out = _mm256_set1_ps(kInfinity);
    for (int a = 0; a < 3; ++a) {
        const __m256 o = _mm256_set1_ps(ray.origin[a]);
        const __m256 inv = _mm256_set1_ps(ray.inverse_direction[a]);
        const __m256 in =
            _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.box[a][ray.near[a]]), o), inv);
        const __m256 out =
            _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.box[a][1 - ray.near[a]]), o), inv);
        t_in = _mm256_max_ps(t_in, in);
        t_out = _mm256_min_ps(t_out, out);
    }
    t_out = _mm256_min_ps(_mm256_mul_ps(t_out, _mm256_set1_ps(kSlabWiden)), _mm256_set1_ps(t_max));
    _mm256_storeu_ps(t_near, t_in);
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(t_in, t_out, _CMP_LE_OQ)));
}

// The least of v's lanes in `lanes` (bit i: lane i; +∞ for none): the others made +∞, then
// halved three times. Exact, as a loop over the lanes would be: min rounds nothing. One
// dependent chain of a dozen instructions in place of a store and a loop of loads (a packet's
// children are ordered by it at every node: docs/PERFORMANCE.md, "A child's nearest entry").
[[gnu::target("avx2")]] inline Real least8(__m256 v, std::uint32_t lanes) {
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i chosen =
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(lanes)), bit), bit);
    __m256 m = _mm256_blendv_ps(_mm256_set1_ps(kInfinity), v, _mm256_castsi256_ps(chosen));
    m = _mm256_min_ps(m, _mm256_permute2f128_ps(m, m, 1));  // halves
    m = _mm256_min_ps(m, _mm256_permute_ps(m, 0b01001110)); // pairs
    m = _mm256_min_ps(m, _mm256_permute_ps(m, 0b10110001)); // neighbours
    return _mm256_cvtss_f32(m);
}

[[gnu::target("avx2")]] inline std::uint32_t
enter_avx2(const PacketRays& packet, const WideBvhNode& n, int k, std::uint32_t active, Real& t) {
    std::uint32_t met = 0;
    for (int g = 0; g < kMaxPacket; g += 8) {
        if (((active >> g) & 255) == 0) continue;
        __m256 t_in = _mm256_setzero_ps(), t_out = _mm256_set1_ps(kInfinity);
        for (int a = 0; a < 3; ++a) {
            const __m256 o = _mm256_load_ps(&packet.origin[a][g]);
            const __m256 inv = _mm256_load_ps(&packet.inverse_direction[a][g]);
            const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(n.box[a][0][k]), o), inv);
            const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(n.box[a][1][k]), o), inv);
            t_in = _mm256_max_ps(t_in, _mm256_min_ps(t0, t1));
            t_out = _mm256_min_ps(t_out, _mm256_max_ps(t0, t1));
        }
        t_out = _mm256_min_ps(_mm256_mul_ps(t_out, _mm256_set1_ps(kSlabWiden)),
                              _mm256_load_ps(&packet.t_max[g]));
        const __m256 inside = _mm256_cmp_ps(t_in, t_out, _CMP_LE_OQ);
        const std::uint32_t lanes =
            static_cast<std::uint32_t>(_mm256_movemask_ps(inside)) & (active >> g) & 255;
        if (lanes == 0) continue;
        met |= lanes << g;
        t = std::min(t, least8(t_in, lanes));
    }
    return met;
}

// _mm512_min_ps and _mm512_max_ps: GCC 12 warns that their unused source is uninitialised (its
// bug 105593); the masked forms with every lane chosen are the same instructions.
[[gnu::target("avx512f")]] inline __m512 min16(__m512 a, __m512 b) {
    return _mm512_mask_min_ps(a, 0xFFFF, a, b);
}
[[gnu::target("avx512f")]] inline __m512 max16(__m512 a, __m512 b) {
    return _mm512_mask_max_ps(a, 0xFFFF, a, b);
}

// least8 for sixteen lanes: halved four times. Not _mm512_mask_reduce_min_ps, which GCC 12
// warns about as above.
[[gnu::target("avx512f")]] inline Real least16(__m512 v, __mmask16 lanes) {
    __m512 m = _mm512_mask_mov_ps(_mm512_set1_ps(kInfinity), lanes, v);
    m = min16(m, _mm512_mask_shuffle_f32x4(m, 0xFFFF, m, m, 0b01001110)); // 256-bit halves
    m = min16(m, _mm512_mask_shuffle_f32x4(m, 0xFFFF, m, m, 0b10110001)); // 128-bit quarters
    m = min16(m, _mm512_mask_permute_ps(m, 0xFFFF, m, 0b01001110));       // pairs
    m = min16(m, _mm512_mask_permute_ps(m, 0xFFFF, m, 0b10110001));       // neighbours
    return _mm512_cvtss_f32(m);
}

[[gnu::target("avx512f")]] inline std::uint32_t
enter_avx512(const PacketRays& packet, const WideBvhNode& n, int k, std::uint32_t active, Real& t) {
    static_assert(kMaxPacket == 16);
    __m512 t_in = _mm512_setzero_ps(), t_out = _mm512_set1_ps(kInfinity);
    for (int a = 0; a < 3; ++a) {
        const __m512 o = _mm512_load_ps(packet.origin[a]);
        const __m512 inv = _mm512_load_ps(packet.inverse_direction[a]);
        const __m512 t0 = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(n.box[a][0][k]), o), inv);
        const __m512 t1 = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(n.box[a][1][k]), o), inv);
        t_in = max16(t_in, min16(t0, t1));
        t_out = min16(t_out, max16(t0, t1));
    }
    t_out = min16(_mm512_mul_ps(t_out, _mm512_set1_ps(kSlabWiden)), _mm512_load_ps(packet.t_max));
    const std::uint32_t met =
        _mm512_mask_cmp_ps_mask(static_cast<__mmask16>(active), t_in, t_out, _CMP_LE_OQ);
    if (met == 0) return 0;
    t = std::min(t, least16(t_in, static_cast<__mmask16>(met)));
    return met;
}
#endif

class WideBvh {
  public:
    WideBvh() = default;
    // The binary tree built with `costs`, collapsed. Where costs.block > 1, every leaf's first
    // slot is a multiple of it, the slots between leaves padding (kEmptyChild in items()), so
    // that a user may keep its items in blocks of that many side by side (a mesh's triangles,
    // four to a SIMD block: trace/shapes/mesh.h).
    explicit WideBvh(std::span<const Bounds> items, LeafCosts costs = kObjectLeaves);

    // This tree over new boxes of the same items (BinaryBvh::refitted's contract).
    WideBvh refitted(std::span<const Bounds> items) const;

    const std::vector<WideBvhNode>& nodes() const { return nodes_; }
    // Item slot → item: leaves name ranges of slots; padding slots hold kEmptyChild.
    const std::vector<std::uint32_t>& items() const { return items_; }
    std::size_t memory_bytes() const {
        return nodes_.size() * sizeof(WideBvhNode) + items_.size() * 4;
    }
    std::size_t node_count() const { return nodes_.size(); }

    // The leaves the ray may meet, nearest box first: visit(first_slot, end_slot, t_max) may
    // shorten t_max and returns true to stop. Counts one node per wide node whose boxes it tests.
    // kNearestFirst false takes each node's children in their own order instead, unsorted: for
    // an any-hit query, whose answer does not depend on the order, the sort is only cost.
    // prefetch(first_slot) is told of every leaf the ray meets as soon as its box is tested, so
    // that the user's data for it (a mesh's triangle block) is fetched while nearer ones are
    // visited: the loads of a node's leaves overlap instead of following one another.
    template <bool kNearestFirst = true, class Counters, class VisitLeaf,
              class PrefetchLeaf = void (*)(std::uint32_t)>
    void traverse_leaves(
        const Ray& ray, Real& t_max, Counters& counters, VisitLeaf&& visit,
        PrefetchLeaf&& prefetch_leaf = [](std::uint32_t) {}) const {
#if GLINT_SIMD
        if (active_kernel() != Kernel::sse) // AVX-512's node test for one ray is AVX2's
            return traverse_leaves_avx2<kNearestFirst>(ray, t_max, counters, visit, prefetch_leaf);
#endif
        traverse_leaves_with<false, kNearestFirst>(ray, t_max, counters, visit, prefetch_leaf);
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
    // each child box is tested against four or eight rays at a time (PacketRays). The test is
    // the single ray's slab test up to which plane is near (taken by min/max rather than by
    // sign), so every ray is offered the leaves its own traversal could be offered (in another
    // order; the visitors' answers do not depend on the order: tests/accel_test.cpp).
    // visit(ray, first_slot, end_slot, t_max) may shorten that ray's limit and returns true when
    // the ray is done (any hit found). t_max[r] is each ray's limit, as in traverse.
    // prefetch_leaf(first_slot) is told of every leaf some ray meets, as traverse_leaves tells it,
    // and the waiting inner children are fetched likewise. kNearestFirst as in traverse_leaves.
    template <bool kNearestFirst = true, class Counters, class VisitLeaf,
              class PrefetchLeaf = void (*)(std::uint32_t)>
    void traverse_packet(
        const Ray* rays, int count, const Real* t_max, Counters& counters, VisitLeaf&& visit,
        PrefetchLeaf&& prefetch_leaf = [](std::uint32_t) {}) const {
#if GLINT_SIMD
        switch (active_kernel()) {
        case Kernel::avx512:
            return traverse_packet_avx512<kNearestFirst>(rays, count, t_max, counters, visit,
                                                         prefetch_leaf);
        case Kernel::avx2:
            return traverse_packet_avx2<kNearestFirst>(rays, count, t_max, counters, visit,
                                                       prefetch_leaf);
        case Kernel::sse:
            break;
        }
#endif
        traverse_packet_with<Kernel::sse, kNearestFirst>(rays, count, t_max, counters, visit,
                                                         prefetch_leaf);
    }

  private:
#if GLINT_SIMD
    // The traversals compiled for AVX2 and AVX-512, their box tests inlined (enter_avx2,
    // enter_avx512).
    template <bool kNearestFirst, class Counters, class VisitLeaf, class PrefetchLeaf>
    [[gnu::target("avx2")]] void traverse_leaves_avx2(const Ray& ray, Real& t_max,
                                                      Counters& counters, VisitLeaf& visit,
                                                      PrefetchLeaf& prefetch_leaf) const {
        traverse_leaves_with<true, kNearestFirst>(ray, t_max, counters, visit, prefetch_leaf);
    }
    template <bool kNearestFirst, class Counters, class VisitLeaf, class PrefetchLeaf>
    [[gnu::target("avx2")]] void traverse_packet_avx2(const Ray* rays, int count, const Real* t_max,
                                                      Counters& counters, VisitLeaf& visit,
                                                      PrefetchLeaf& prefetch_leaf) const {
        traverse_packet_with<Kernel::avx2, kNearestFirst>(rays, count, t_max, counters, visit,
                                                          prefetch_leaf);
    }
    template <bool kNearestFirst, class Counters, class VisitLeaf, class PrefetchLeaf>
    [[gnu::target("avx512f")]] void
    traverse_packet_avx512(const Ray* rays, int count, const Real* t_max, Counters& counters,
                           VisitLeaf& visit, PrefetchLeaf& prefetch_leaf) const {
        traverse_packet_with<Kernel::avx512, kNearestFirst>(rays, count, t_max, counters, visit,
                                                            prefetch_leaf);
    }
#endif

    // traverse_leaves with the AVX2 kernel's box test or the portable one's.
    template <bool kAvx2, bool kNearestFirst, class Counters, class VisitLeaf, class PrefetchLeaf>
    [[gnu::always_inline]] void traverse_leaves_with(const Ray& ray, Real& t_max,
                                                     Counters& counters, VisitLeaf& visit,
                                                     PrefetchLeaf& prefetch_leaf) const {
        if (nodes_.empty()) return;
        const WideRay wide(ray);
        struct Entry {
            std::uint32_t child, count;
            Real t; // where the ray enters the child's box
        };
        // At most seven children a level wait on the stack; the depth is the binary tree's.
        Entry stack[(kBvhWidth - 1) * kMaxBvhDepth + 1];
        int top = 0;
        std::uint32_t node = 0;
        for (;;) {
            counters.node();
            const WideBvhNode& n = nodes_[node];
            Real t_near[kBvhWidth];
            unsigned mask;
#if GLINT_SIMD
            if constexpr (kAvx2)
                mask = enter_avx2(wide, n, t_max, t_near);
            else
#endif
                mask = wide.enter_sse(n, t_max, t_near);
            // The children the ray meets, nearest first (insertion into at most eight) where asked.
            Entry hit[kBvhWidth];
            int hits = 0;
            for (; mask != 0; mask &= mask - 1) {
                const int k = __builtin_ctz(mask);
                const Entry e{n.child[k], n.count[k], t_near[k]};
                int at = hits++;
                if constexpr (kNearestFirst)
                    for (; at > 0 && hit[at - 1].t > e.t; --at) hit[at] = hit[at - 1];
                hit[at] = e;
            }
            for (int k = hits - 1; k > 0; --k) {
                // A waiting child is fetched while the nearer ones are traversed.
                if (hit[k].count == 0)
                    prefetch(hit[k].child);
                else
                    prefetch_leaf(hit[k].child);
                stack[top++] = hit[k];
            }
            if (hits > 0 && hit[0].count > 0) prefetch_leaf(hit[0].child);
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

    // traverse_packet with the box test of kernel K.
    template <Kernel K, bool kNearestFirst, class Counters, class VisitLeaf, class PrefetchLeaf>
    [[gnu::always_inline]] void traverse_packet_with(const Ray* rays, int count, const Real* t_max,
                                                     Counters& counters, VisitLeaf& visit,
                                                     PrefetchLeaf& prefetch_leaf) const {
        assert(count <= kMaxPacket);
        if (nodes_.empty() || count == 0) return;
        PacketRays packet(rays, count, t_max);
        using Mask = PacketRays::Mask;
        struct Entry {
            std::uint32_t child, count;
            Mask rays; // the rays that met the child's box
            Real t;    // the nearest of their entry distances: the order children are taken in
        };
        Entry stack[(kBvhWidth - 1) * kMaxBvhDepth + 1];
        int top = 0;
        Mask done = 0; // rays whose visitor said they are finished
        Entry next{0, 0, packet.all, 0};
        for (;;) {
            if (next.count == 0) { // an inner node: which rays meet each of its children
                const WideBvhNode& n = nodes_[next.child];
                const Mask active = next.rays & ~done;
                for (Mask m = active; m != 0; m &= m - 1) counters.node(); // per ray, as alone
                Entry hit[kBvhWidth];
                int hits = 0;
                for (int k = 0; k < kBvhWidth; ++k) {
                    if (n.child[k] == kEmptyChild) continue;
                    Real t = kInfinity;
                    Mask met;
#if GLINT_SIMD
                    if constexpr (K == Kernel::avx512)
                        met = enter_avx512(packet, n, k, active, t);
                    else if constexpr (K == Kernel::avx2)
                        met = enter_avx2(packet, n, k, active, t);
                    else
#endif
                        met = packet.enter_sse(n, k, active, t);
                    if (met == 0) continue;
                    const Entry e{n.child[k], n.count[k], met, t};
                    int at = hits++; // nearest first where asked
                    if constexpr (kNearestFirst)
                        for (; at > 0 && hit[at - 1].t > e.t; --at) hit[at] = hit[at - 1];
                    hit[at] = e;
                }
                for (int k = hits - 1; k >= 0; --k) {
                    if (hit[k].count > 0)
                        prefetch_leaf(hit[k].child);
                    else if (k > 0)
                        prefetch(hit[k].child);
                    if (k > 0) stack[top++] = hit[k];
                }
                if (hits > 0) {
                    next = hit[0];
                    continue;
                }
            } else { // a leaf: each ray that met its box visits it
                for (Mask active = next.rays & ~done; active != 0; active &= active - 1) {
                    const int r = __builtin_ctz(active);
                    if (visit(r, next.child, next.child + next.count, packet.t_max[r]))
                        done |= Mask{1} << r;
                }
            }
            do { // the next waiting child some unfinished ray still reaches
                if (top == 0) return;
                next = stack[--top];
                next.rays &= ~done & packet.reaching(next.t);
            } while (next.rays == 0);
        }
    }

    void prefetch(std::uint32_t node) const {
        prefetch_bytes(&nodes_[node], sizeof(WideBvhNode));
    }

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
