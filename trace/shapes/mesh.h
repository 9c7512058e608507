// Triangles and indexed triangle meshes (counter-clockwise front), in object space.
#pragma once

#include "trace/accel/wide_bvh.h"
#include "trace/bounds.h"
#include "trace/shapes/shape.h"
#include "trace/texture.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

// Four triangles side by side, structure of arrays: corner k's coordinate along axis a of the
// triangle in lane i is p[k][a][i]. 160 bytes in float: one triangle test of four lanes loads
// nine vectors and nothing else (no index, no vertex lookup), and a lane that is hit finds its
// triangle's index beside them, in the cache lines just read (as Embree's blocks keep their
// primitive ids) rather than in a separate slot → triangle table.
inline constexpr std::uint32_t kTriangleLanes = 4;
struct alignas(16) TriangleBlock {
    Real p[3][3][kTriangleLanes];
    std::uint32_t triangle[kTriangleLanes]; // its index in Mesh::triangles; padding: kEmptyChild
    Vec3 corner(int k, std::uint32_t lane) const {
        return {p[k][0][lane], p[k][1][lane], p[k][2][lane]};
    }
};

// A mesh's tree: a leaf of one block (up to four triangles) is never split, a level costs two
// block tests, and a leaf holds up to three blocks. On the 10⁶-triangle terrain the tree has
// 20,834 nodes instead of 54,669 (leaves of at most one block, no level cost): closest hits
// 0.87–0.96, packets 0.83, shadow rays 0.72 of the time (medians; bench/accel_bench.cpp;
// docs/PERFORMANCE.md, "Mesh leaves of up to three blocks"); SPD's smaller meshes about the
// same.
inline constexpr LeafCosts kTriangleLeaves{kTriangleLanes, 2, 12};

// A scene's triangle mesh prepared for tracing (see prepare_mesh).
struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles; // indices into vertices
    std::vector<Vec3> normals;         // per vertex, or empty (flat shading)
    std::vector<glm::vec2> uvs, uvs1;  // texture coordinates per vertex (sets 0 and 1), or empty
    std::vector<glm::vec3> colours;    // colours per vertex, or empty
    std::vector<glm::vec4> tangents;   // tangents per vertex (w: the bitangent's sign), or empty
    Bounds bounds;                     // of the vertices, object space
    // Over the triangles, object space; every leaf starts at a multiple of kTriangleLanes, so
    // that its triangles fill whole blocks (a leaf of up to four is one block).
    WideBvh bvh;
    // The corners and index of the triangle in slot s in blocks[s / 4], lane s % 4: in the
    // BVH's slot order where there is one (slot s holds triangle bvh.items()[s]; padding slots
    // hold a degenerate triangle that no leaf names), else in triangle order.
    std::vector<TriangleBlock> blocks;
    Vec3 corner(std::uint32_t slot, int k) const {
        return blocks[slot / kTriangleLanes].corner(k, slot % kTriangleLanes);
    }
};

// Each triangle's box, object space.
inline std::vector<Bounds> triangle_bounds(const Mesh& mesh) {
    std::vector<Bounds> boxes;
    boxes.reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) {
        Bounds b;
        b.extend(mesh.vertices[t.x]), b.extend(mesh.vertices[t.y]), b.extend(mesh.vertices[t.z]);
        boxes.push_back(padded(b));
    }
    return boxes;
}

struct TriangleHit {
    Real t = kInfinity;
    Real u = 0, v = 0; // barycentric weights of vertices 1 and 2
};

// A ray prepared for the watertight test (Woop, Benthin & Wald, JCGT 2013): the axis of its
// largest direction component becomes z, and a shear makes the ray the +z axis, so that each
// triangle is tested in 2D with edge functions that neighbouring triangles compute identically:
// a ray through a shared edge hits one of them, never neither. Computed once per ray.
struct WatertightRay {
    Vec3 origin;
    int kx, ky, kz;
    Real sx, sy, sz;

    explicit WatertightRay(const Ray& ray) : origin(ray.origin) {
        const Vec3 a = glm::abs(ray.direction);
        kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
        kx = (kz + 1) % 3;
        ky = (kx + 1) % 3;
        if (ray.direction[kz] < 0) std::swap(kx, ky); // keep the winding
        sx = ray.direction[kx] / ray.direction[kz];
        sy = ray.direction[ky] / ray.direction[kz];
        sz = 1.0_r / ray.direction[kz];
    }
};

inline TriangleHit intersect_triangle(Vec3 p0, Vec3 p1, Vec3 p2, const WatertightRay& r) {
    const Vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
    const Real ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
    const Real bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
    const Real cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
    Real u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    if (u == 0 || v == 0 || w == 0) { // on an edge in float: decide in double, as the paper does
        u = static_cast<Real>(double(cx) * by - double(cy) * bx);
        v = static_cast<Real>(double(ax) * cy - double(ay) * cx);
        w = static_cast<Real>(double(bx) * ay - double(by) * ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return {};
    const Real det = u + v + w;
    if (det == 0) return {};
    const Real t = (u * r.sz * a[r.kz] + v * r.sz * b[r.kz] + w * r.sz * c[r.kz]) / det;
    return {t, v / det, w / det};
}

inline TriangleHit intersect_triangle(Vec3 p0, Vec3 p1, Vec3 p2, const Ray& ray) {
    return intersect_triangle(p0, p1, p2, WatertightRay(ray));
}

// Up to four triangles of a block (lanes [0, lanes)) against one ray. Returns the lanes that
// may be hit, bit i for lane i: for those, hits[i] = intersect_triangle(the corners of lane i,
// ray), bit for bit; every other lane below `lanes` is missed (intersect_triangle's
// TriangleHit{}) and its hits[i] is left as it was. With SSE in float, the test's operations in
// the same order lane by lane, four lanes an instruction, and the divisions only when a lane
// is left after the edge functions' signs (most blocks a ray reaches are missed, and waiting on
// their three divisions was the largest stall in gears-4's triangle tests); a lane whose edge
// functions meet a zero (the ray through an edge or a vertex in float) is answered by the single
// test, which decides it in double. Elsewhere (double precision), one lane at a time.
[[nodiscard, gnu::always_inline]] inline unsigned
intersect_triangles(const TriangleBlock& block, std::uint32_t lanes, const WatertightRay& r,
                    TriangleHit (&hits)[kTriangleLanes]) {
#if GLINT_SIMD
    const int axis[3] = {r.kx, r.ky, r.kz};
    __m128 x[3], y[3], z[3]; // corner k relative to the origin, sheared: x, y; and along kz
    const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy);
    for (int k = 0; k < 3; ++k) {
        __m128 d[3];
        for (int a = 0; a < 3; ++a)
            d[a] = _mm_sub_ps(_mm_load_ps(block.p[k][axis[a]]), _mm_set1_ps(r.origin[axis[a]]));
        x[k] = _mm_sub_ps(d[0], _mm_mul_ps(sx, d[2]));
        y[k] = _mm_sub_ps(d[1], _mm_mul_ps(sy, d[2]));
        z[k] = d[2];
    }
    // u = cx·by − cy·bx, v = ax·cy − ay·cx, w = bx·ay − by·ax (corners a, b, c = 0, 1, 2).
    const __m128 u = _mm_sub_ps(_mm_mul_ps(x[2], y[1]), _mm_mul_ps(y[2], x[1]));
    const __m128 v = _mm_sub_ps(_mm_mul_ps(x[0], y[2]), _mm_mul_ps(y[0], x[2]));
    const __m128 w = _mm_sub_ps(_mm_mul_ps(x[1], y[0]), _mm_mul_ps(y[1], x[0]));
    const __m128 zero = _mm_setzero_ps();
    const __m128 on_edge =
        _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero));
    const __m128 negative =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
    const __m128 positive =
        _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
    const __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
    const __m128 missed = _mm_or_ps(_mm_and_ps(negative, positive), _mm_cmpeq_ps(det, zero));
    const unsigned all = (1u << lanes) - 1;
    const unsigned edges = static_cast<unsigned>(_mm_movemask_ps(on_edge)) & all;
    const unsigned crossed = ~static_cast<unsigned>(_mm_movemask_ps(missed)) & all & ~edges;
    if ((crossed | edges) == 0) return 0;
    const __m128 sz = _mm_set1_ps(r.sz);
    const __m128 t = _mm_div_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(u, sz), z[0]),
                                                      _mm_mul_ps(_mm_mul_ps(v, sz), z[1])),
                                           _mm_mul_ps(_mm_mul_ps(w, sz), z[2])),
                                det);
    // A missed lane is TriangleHit{}: t = ∞, u = v = 0.
    alignas(16) Real t_out[4], b1[4], b2[4];
    _mm_store_ps(t_out,
                 _mm_or_ps(_mm_andnot_ps(missed, t), _mm_and_ps(missed, _mm_set1_ps(kInfinity))));
    _mm_store_ps(b1, _mm_andnot_ps(missed, _mm_div_ps(v, det)));
    _mm_store_ps(b2, _mm_andnot_ps(missed, _mm_div_ps(w, det)));
    for (std::uint32_t i = 0; i < lanes; ++i)
        if ((edges >> i) & 1)
            hits[i] =
                intersect_triangle(block.corner(0, i), block.corner(1, i), block.corner(2, i), r);
        else if ((crossed >> i) & 1)
            hits[i] = {t_out[i], b1[i], b2[i]};
    return crossed | edges;
#else
    unsigned may_hit = 0;
    for (std::uint32_t i = 0; i < lanes; ++i) {
        hits[i] = intersect_triangle(block.corner(0, i), block.corner(1, i), block.corner(2, i), r);
        may_hit |= unsigned{hits[i].t < kInfinity} << i;
    }
    return may_hit;
#endif
}

// Builds what intersect_mesh reads: the vertices and their bounds (padded(), as the triangles'
// boxes are), above 8 triangles a BVH over them (the bottom level of a two-level structure: to the
// top level a mesh is one object), and every triangle's corners in blocks in the order the BVH
// reads them.
inline Mesh prepare_mesh(const TriangleMesh& given) {
    Mesh mesh;
    mesh.triangles = given.triangles;
    mesh.vertices.reserve(given.vertices.size());
    for (const glm::vec3& v : given.vertices) {
        mesh.vertices.push_back(Vec3(v));
        mesh.bounds.extend(mesh.vertices.back());
    }
    mesh.bounds = padded(mesh.bounds);
    for (const glm::vec3& n : given.normals) mesh.normals.push_back(Vec3(n));
    mesh.uvs = given.uvs;
    mesh.uvs1 = given.uvs1;
    mesh.colours = given.colours;
    mesh.tangents = given.tangents;
    if (mesh.triangles.size() > 8) mesh.bvh = WideBvh(triangle_bounds(mesh), kTriangleLeaves);
    const bool tree = !mesh.bvh.nodes().empty();
    const std::size_t slots = tree ? mesh.bvh.items().size() : mesh.triangles.size();
    TriangleBlock padding{}; // all corners 0
    std::fill(std::begin(padding.triangle), std::end(padding.triangle), kEmptyChild);
    mesh.blocks.assign((slots + kTriangleLanes - 1) / kTriangleLanes, padding);
    for (std::uint32_t slot = 0; slot < slots; ++slot) {
        const std::uint32_t triangle = tree ? mesh.bvh.items()[slot] : slot;
        if (triangle == kEmptyChild) continue;
        const glm::uvec3 t = mesh.triangles[triangle];
        const Vec3 corners[3] = {mesh.vertices[t.x], mesh.vertices[t.y], mesh.vertices[t.z]};
        TriangleBlock& block = mesh.blocks[slot / kTriangleLanes];
        block.triangle[slot % kTriangleLanes] = triangle;
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) block.p[k][a][slot % kTriangleLanes] = corners[k][a];
    }
    return mesh;
}

// Asks for the first block of the leaf at slot `first` (its 160 bytes) to be fetched.
inline void prefetch_block(const Mesh& mesh, std::uint32_t first) {
    prefetch_bytes(&mesh.blocks[first / kTriangleLanes], sizeof(TriangleBlock));
}

// The mesh's texture coordinate set `set` (0 or 1): empty where it has none.
inline const std::vector<glm::vec2>& mesh_uvs(const Mesh& mesh, int set) {
    return set == 1 ? mesh.uvs1 : mesh.uvs;
}

// The texture coordinates of set `set` at barycentric weights (u, v) of triangle `triangle`,
// interpolated as the surface is (mesh_surface); the mesh must have them.
inline glm::vec2 mesh_uv(const Mesh& mesh, std::uint32_t triangle, Real u, Real v, int set = 0) {
    const std::vector<glm::vec2>& uvs = mesh_uvs(mesh, set);
    const glm::uvec3 tri = mesh.triangles[triangle];
    const float b1 = static_cast<float>(u), b2 = static_cast<float>(v);
    return (1.0f - b1 - b2) * uvs[tri.x] + b1 * uvs[tri.y] + b2 * uvs[tri.z];
}

// The alpha of a cut-out material at barycentric weights (u, v) of a triangle (DESIGN §13): the
// factor times the texture's alpha there, where there is a texture and the mesh has its texture
// coordinates (as shading samples its colour).
inline float cut_out_alpha(const Mesh& mesh, const CutOut& cut, std::uint32_t triangle, Real u,
                           Real v) {
    if (!cut.texture || mesh_uvs(mesh, cut.texture->set).empty()) return cut.alpha;
    return cut.alpha * sample_alpha(*cut.texture, mesh_uv(mesh, triangle, u, v, cut.texture->set));
}

// Whether a hit there is cut away: no hit, the ray goes on.
inline bool cut_away(const Mesh& mesh, const CutOut& cut, std::uint32_t triangle, Real u, Real v) {
    return cut.cuts && cut_out_alpha(mesh, cut, triangle, u, v) < cut.cutoff;
}

// Whether the ray `r` was prepared from meets triangle `triangle` from behind: its winding
// normal (p1 − p0) × (p2 − p0) does not point back along the ray. The direction is the one the
// preparation divided out (d[kz] = 1/sz, d[kx] = sx/sz, d[ky] = sy/sz: up to its length), so
// only one-sided meshes' hits pay for it, not every triangle test.
inline bool seen_from_behind(const Mesh& mesh, std::uint32_t triangle, const WatertightRay& r) {
    const glm::uvec3 t = mesh.triangles[triangle];
    const Vec3 &p0 = mesh.vertices[t.x], &p1 = mesh.vertices[t.y], &p2 = mesh.vertices[t.z];
    Vec3 d;
    d[r.kz] = 1 / r.sz, d[r.kx] = r.sx / r.sz, d[r.ky] = r.sy / r.sz;
    return glm::dot(glm::cross(p1 - p0, p2 - p0), d) >= 0;
}

// Whether `cut` makes a hit there no hit: a one-sided triangle seen from behind, or cut away.
inline bool filtered_away(const Mesh& mesh, const CutOut& cut, std::uint32_t triangle,
                          const TriangleHit& h, const WatertightRay& r) {
    if (cut.one_sided && seen_from_behind(mesh, triangle, r)) return true;
    return cut_away(mesh, cut, triangle, h.u, h.v);
}

// The triangles in slots [begin, end) (begin a multiple of kTriangleLanes) for one ray, a block
// at a time: a triangle replaces `best` when it is hit in (0, t_max) nearer, or as near with a
// lower triangle index, and is not filtered away where `cut` is given. The one test of
// intersect_mesh and intersect_mesh_packet.
template <class Counters>
[[gnu::always_inline]] inline void
consider_triangles(const Mesh& mesh, std::uint32_t begin, std::uint32_t end,
                   const WatertightRay& ray, Real t_max, ShapeHit& best, Counters& counters,
                   const CutOut* cut) {
    for (std::uint32_t first = begin; first < end; first += kTriangleLanes) {
        const std::uint32_t lanes = std::min(kTriangleLanes, end - first);
        const TriangleBlock& block = mesh.blocks[first / kTriangleLanes];
        TriangleHit hits[kTriangleLanes];
        const unsigned may_hit = intersect_triangles(block, lanes, ray, hits);
        for (std::uint32_t i = 0; i < lanes; ++i) counters.primitive();
        for (unsigned m = may_hit; m != 0; m &= m - 1) {
            const unsigned i = static_cast<unsigned>(__builtin_ctz(m));
            const TriangleHit& h = hits[i];
            const std::uint32_t triangle = block.triangle[i];
            if (h.t > 0 && h.t < t_max &&
                (h.t < best.t || (h.t == best.t && triangle < best.part)) &&
                !(cut && filtered_away(mesh, *cut, triangle, h, ray)))
                best = {h.t, triangle, h.u, h.v};
        }
    }
}

// The nearest triangle below t_max: through the mesh's own BVH (the bottom level of a two-level
// structure), or, for meshes too small to have one, all of them. Boxes are pruned against the
// limit loosely (loose(), trace/math.h), triangles strictly. On equal t the lower triangle index
// wins, as it does when all are tested in order: the answer does not depend on the order a
// tree visits its leaves in (tests/accel_test.cpp, MeshHitsAreTheSameWhateverTheVisitingOrder).
// Wanted::any stops after the first leaf that holds a hit: a hit, not always the nearest, found
// exactly when the nearest is (every leaf the nearest-first traversal could reach is reached,
// unsorted: kNearestFirst false, its limit only shortened).
// With `cut`, hits it cuts away are no hits (the traversal goes on past them).
template <class Counters>
ShapeHit intersect_mesh(const Mesh& mesh, const Ray& ray, Real t_max, Counters& counters,
                        Wanted wanted = Wanted::nearest, const CutOut* cut = nullptr) {
    ShapeHit best;
    const WatertightRay prepared(ray); // once per ray, not per triangle
    Real box_limit = loose(t_max);
    if (!mesh.bvh.nodes().empty()) {
        const auto visit = [&](std::uint32_t begin, std::uint32_t end, Real& limit) {
            consider_triangles(mesh, begin, end, prepared, t_max, best, counters, cut);
            limit = loose(std::min(best.t, t_max));
            return wanted == Wanted::any && best.found();
        };
        const auto prefetch = [&](std::uint32_t first) { prefetch_block(mesh, first); };
        if (wanted == Wanted::any) // any leaf with a hit will do: no order to keep
            mesh.bvh.traverse_leaves<false>(ray, box_limit, counters, visit, prefetch);
        else
            mesh.bvh.traverse_leaves(ray, box_limit, counters, visit, prefetch);
    } else {
        if (!SlabRay(ray).hits(mesh.bounds, box_limit)) return {};
        consider_triangles(mesh, 0, static_cast<std::uint32_t>(mesh.triangles.size()), prepared,
                           t_max, best, counters, cut);
    }
    return best;
}

// intersect_mesh for `count` ≤ kMaxPacket coherent rays at once (an item buffer's block of
// pixels that name the mesh, a tile's camera or shadow rays): best[r] = intersect_mesh(mesh,
// rays[r], t_max[r], counters, wanted, cut), bit for bit where `wanted` is the nearest hit; for
// Wanted::any, found exactly where that is (the hit itself may be another). Through the mesh's
// BVH as a packet (WideBvh::traverse_packet, which offers each ray the leaves its own traversal
// could be offered, in another order; the tie rule makes the order irrelevant); a mesh without
// one, ray by ray.
template <class Counters>
void intersect_mesh_packet(const Mesh& mesh, const Ray* rays, int count, const Real* t_max,
                           ShapeHit* best, Counters& counters, Wanted wanted = Wanted::nearest,
                           const CutOut* cut = nullptr) {
    if (mesh.bvh.nodes().empty()) {
        for (int r = 0; r < count; ++r)
            best[r] = intersect_mesh(mesh, rays[r], t_max[r], counters, wanted, cut);
        return;
    }
    std::optional<WatertightRay> prepared[kMaxPacket]; // made on a ray's first leaf
    Real box_limit[kMaxPacket];
    for (int r = 0; r < count; ++r) best[r] = {}, box_limit[r] = loose(t_max[r]);
    const auto visit = [&](int r, std::uint32_t begin, std::uint32_t end, Real& limit) {
        if (!prepared[r]) prepared[r].emplace(rays[r]);
        consider_triangles(mesh, begin, end, *prepared[r], t_max[r], best[r], counters, cut);
        limit = loose(std::min(best[r].t, t_max[r]));
        return wanted == Wanted::any && best[r].found();
    };
    const auto prefetch = [&](std::uint32_t first) { prefetch_block(mesh, first); };
    if (wanted == Wanted::any)
        mesh.bvh.traverse_packet<false>(rays, count, box_limit, counters, visit, prefetch);
    else
        mesh.bvh.traverse_packet(rays, count, box_limit, counters, visit, prefetch);
}

// The surface at barycentric weights (u, v) of triangle `triangle`'s vertices 1 and 2, as its
// intersection found them (ShapeHit::u, v).
inline SurfaceSample mesh_surface(const Mesh& mesh, std::uint32_t triangle, Real u, Real v) {
    const glm::uvec3 tri = mesh.triangles[triangle];
    // References, not copies: GCC copied each corner through the stack in two stores read back
    // by one load that spans them, which the store buffer cannot forward (a fifth of the
    // function's time on balls-4's floor: docs/PERFORMANCE.md, "Three stalls the profiler named").
    const Vec3 &p0 = mesh.vertices[tri.x], &p1 = mesh.vertices[tri.y], &p2 = mesh.vertices[tri.z];
    const Real b0 = 1.0_r - u - v;
    // Barycentric interpolation keeps the point on the triangle's plane up to γ7·Σ|bᵢ·pᵢ|
    // (pbrt-v4, Triangle::InteractionFromIntersection).
    const Vec3 point = b0 * p0 + u * p1 + v * p2;
    const Vec3 error = gamma(7) * (glm::abs(b0 * p0) + glm::abs(u * p1) + glm::abs(v * p2));
    const Vec3 facet = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    if (mesh.normals.empty()) return {point, facet, error};
    // Smooth shading (Phong): the vertex normals interpolated with the hit's barycentrics.
    const Vec3 shading =
        b0 * mesh.normals[tri.x] + u * mesh.normals[tri.y] + v * mesh.normals[tri.z];
    return {point, facet, error, shading};
}

// Triangles and meshes in the shape table (trace/shapes/table.h): a triangle is a mesh of one
// triangle, given by its 3 vertices.
struct MeshShape {
    static constexpr std::string_view name = "mesh";
    static constexpr ShapeTraits traits{.raster = RasterAs::triangles,
                                        .keys = {.vertices = true, .indices = true, .file = true}};

    static ObjectBox bounds(const SceneObject& object, const std::vector<TriangleMesh>& meshes) {
        DVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        for (const glm::vec3& v : meshes[object.mesh].vertices)
            lo = glm::min(lo, DVec3(v)), hi = glm::max(hi, DVec3(v));
        return {lo, hi};
    }
    template <class Counters>
    static ShapeHit intersect(const ShapeParams& shape, const Ray& ray, Real t_max,
                              Counters& counters) {
        return intersect_mesh(*shape.mesh, ray, t_max, counters, Wanted::nearest, shape.cut_out);
    }
    static SurfaceSample surface(const ShapeParams& shape, Vec3, const Hit& hit) {
        return mesh_surface(*shape.mesh, hit.primitive, hit.u, hit.v);
    }
};

struct Triangle : MeshShape {
    static constexpr std::string_view name = "triangle";
    static constexpr ShapeTraits traits{
        .convex = true, .planar = true, .raster = RasterAs::triangles, .keys = {.vertices = true}};
};

} // namespace GLINT_PRECISION
} // namespace glint
