// The SIMD kernels answer exactly what the single tests they stand for answer, bit for bit, on
// millions of random cases built to hit their corners: rays through vertices and edges (where
// the watertight test falls back to double), rays in a triangle's plane, degenerate triangles
// (repeated corners, collinear, zero area), tiny and huge coordinates, and blocks of every fill.
#include "test_scenes.h"

#include "trace/kernel.h"
#include "trace/shapes/cylinder.h"
#include "trace/shapes/mesh.h"
#include "trace/shapes/sphere.h"
#include "trace/transform.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>

namespace glint {
namespace {

// Equal to the bit (NaN included, as the same NaN).
::testing::AssertionResult same_hit(const TriangleHit& got, const TriangleHit& expected) {
    if (std::bit_cast<std::uint32_t>(static_cast<float>(got.t)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.t)) &&
        std::bit_cast<std::uint32_t>(static_cast<float>(got.u)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.u)) &&
        std::bit_cast<std::uint32_t>(static_cast<float>(got.v)) ==
            std::bit_cast<std::uint32_t>(static_cast<float>(expected.v)))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "got t " << got.t << " u " << got.u << " v " << got.v << ", expected t " << expected.t
           << " u " << expected.u << " v " << expected.v;
}

// A random triangle of one of several kinds, at a random scale and offset.
std::array<Vec3, 3> random_triangle(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    std::array<Vec3, 3> p{Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)),
                          Vec3(u(rng), u(rng), u(rng))};
    switch (rng() % 8) {
    case 0: // two corners the same
        p[rng() % 3] = p[(rng() % 2) + 1 == 1 ? 0 : 1];
        break;
    case 1: // collinear
        p[2] = p[0] + 0.5f * (p[1] - p[0]);
        break;
    case 2: // on an integer lattice, sharing planes and edges with its neighbours
        for (Vec3& c : p) c = glm::round(4.0f * c);
        break;
    case 3: // axis-aligned plane
        p[0].y = p[1].y = p[2].y = 0.25f;
        break;
    default:
        break;
    }
    static constexpr float kScales[] = {1e-6f, 1e-3f, 1, 1e3f, 1e6f};
    const float scale = kScales[rng() % 5];
    const Vec3 offset =
        rng() % 3 == 0 ? Vec3(1e5f * u(rng), 1e5f * u(rng), 1e5f * u(rng)) : Vec3(0.0f);
    for (Vec3& c : p) c = c * scale + offset;
    return p;
}

// A ray aimed at a point of the triangle that decides watertightness (a corner, an edge's
// midpoint), inside it, or past it; or lying in its plane (grazing); or axis-parallel.
Ray ray_at(const std::array<Vec3, 3>& p, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1), w(0, 1);
    const float size = glm::length(p[1] - p[0]) + glm::length(p[2] - p[0]) + 1e-30f;
    Vec3 target;
    switch (rng() % 5) {
    case 0:
        target = p[rng() % 3];
        break;
    case 1:
        target = 0.5f * (p[rng() % 3] + p[rng() % 3]);
        break;
    case 2: {
        const float a = w(rng), b = w(rng) * (1 - a);
        target = p[0] + a * (p[1] - p[0]) + b * (p[2] - p[0]);
        break;
    }
    default:
        target = p[0] + size * Vec3(u(rng), u(rng), u(rng));
        break;
    }
    Vec3 origin = target + 3.0f * size * Vec3(u(rng), u(rng), u(rng));
    switch (rng() % 6) {
    case 0: // in the triangle's plane (as nearly as float puts it)
        origin = p[0] + 2.0f * (p[0] - target);
        break;
    case 1: // axis-parallel
        origin = target, origin[rng() % 3] += (rng() % 2 ? 1.0f : -1.0f) * 3 * size;
        break;
    default:
        break;
    }
    Vec3 direction = target - origin;
    if (direction == Vec3(0.0f)) direction = {0, 0, 1};
    return {origin, direction};
}

// intersect_triangles (a block of up to four triangles against one ray; the lanes it names, and
// a miss for the others) against intersect_triangle lane by lane: 4 million rays in Release, each
// at one of its block's triangles, so that the corner cases are met in every lane.
TEST(Kernel, TriangleBlocksAgreeExactlyWithTheSingleTest) {
    std::mt19937 rng(7);
    const int blocks = testing::kUnderSanitizers ? 20000 : 200000;
    std::uint64_t hits = 0, edge_cases = 0, tests = 0;
    for (int b = 0; b < blocks; ++b) {
        const std::uint32_t lanes = 1 + rng() % kTriangleLanes;
        TriangleBlock block{};
        std::array<Vec3, 3> triangles[kTriangleLanes];
        for (std::uint32_t i = 0; i < lanes; ++i) {
            triangles[i] = i > 0 && rng() % 4 == 0 ? triangles[i - 1] : random_triangle(rng);
            if (i > 0 && rng() % 4 == 0) // a neighbour: shares an edge with the one before
                triangles[i][2] = triangles[i - 1][0] + triangles[i - 1][1] - triangles[i - 1][2];
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a) block.p[k][a][i] = triangles[i][k][a];
        }
        for (int r = 0; r < 20; ++r) {
            const WatertightRay ray(ray_at(triangles[rng() % lanes], rng));
            TriangleHit got[kTriangleLanes];
            const unsigned may_hit = intersect_triangles(block, lanes, ray, got);
            ASSERT_EQ(may_hit >> lanes, 0u) << "block " << b << " ray " << r;
            for (std::uint32_t i = 0; i < lanes; ++i) {
                const std::array<Vec3, 3>& t = triangles[i];
                const TriangleHit expected = intersect_triangle(t[0], t[1], t[2], ray);
                // A lane left out is a miss; a lane named is the single test's answer.
                const TriangleHit answer = (may_hit >> i) & 1 ? got[i] : TriangleHit{};
                ASSERT_TRUE(same_hit(answer, expected))
                    << "block " << b << " ray " << r << " lane " << i;
                ++tests;
                hits += expected.t < kInfinity;
                edge_cases += expected.u == 0 || expected.v == 0;
            }
        }
    }
    EXPECT_GT(hits, tests / 5) << "too few hits to mean much";
    EXPECT_GT(edge_cases, tests / 100) << "too few rays through edges and corners";
}

// Every kernel this processor has (and the portable one, SSE, always) tests an eight-wide
// node's boxes exactly as SlabRay::clip's arithmetic does lane by lane: the same lanes met and
// the same entry distances, bit for bit, for single rays (WideRay::enter) and packets of every
// fill (PacketRays::enter). Boxes empty, flat, touching the ray's origin, huge; rays
// axis-parallel (reciprocals ±1e30), from inside, with limits 0, finite and infinite.
TEST(Kernel, EveryKernelTestsNodeBoxesExactlyAsTheScalarSlabTest) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    const std::vector<Kernel> kernels = available_kernels();
    ASSERT_EQ(kernels.front(), Kernel::sse);
    const auto random_node = [&] {
        WideBvhNode n{};
        for (int k = 0; k < kBvhWidth; ++k) {
            Vec3 lo(u(rng), u(rng), u(rng)), hi = lo + Vec3(u(rng), u(rng), u(rng)) + 1.0f;
            switch (rng() % 6) {
            case 0: // an empty lane
                lo = Vec3(kInfinity), hi = Vec3(-kInfinity);
                break;
            case 1: // flat along one axis
                hi[rng() % 3] = lo[rng() % 3];
                break;
            case 2: // huge
                lo *= 1e30f, hi *= 1e30f;
                break;
            default:
                break;
            }
            n.child[k] = lo.x == kInfinity ? kEmptyChild : 0;
            for (int a = 0; a < 3; ++a)
                n.box[a][0][k] = lo[a],
                n.box[a][1][k] = n.child[k] ? hi[a] : std::max(lo[a], hi[a]);
        }
        return n;
    };
    const auto random_ray = [&](const WideBvhNode& n) {
        Vec3 origin(2 * u(rng), 2 * u(rng), 2 * u(rng)), direction(u(rng), u(rng), u(rng));
        const int k = static_cast<int>(rng() % kBvhWidth);
        if (n.child[k] != kEmptyChild && rng() % 3 == 0) // towards a lane's box
            for (int a = 0; a < 3; ++a)
                direction[a] = (n.box[a][0][k] + n.box[a][1][k]) / 2 - origin[a] + 0.3f * u(rng);
        else if (n.child[k] != kEmptyChild && rng() % 2) // through a corner: enters as it leaves
            for (int a = 0; a < 3; ++a) direction[a] = n.box[a][rng() % 2][k] - origin[a];
        if (rng() % 4 == 0) direction[rng() % 3] = 0;
        if (rng() % 8 == 0) direction = Vec3(0), direction[rng() % 3] = rng() % 2 ? 1.0f : -1.0f;
        if (direction == Vec3(0.0f)) direction = {0, 1, 0};
        return Ray{origin, direction};
    };
    const Real limits[] = {0, 0.5f, 3, 1e30f, kInfinity};
    std::uint64_t met = 0, lanes = 0;
    const int nodes = testing::kUnderSanitizers ? 20000 : 200000;
    for (int i = 0; i < nodes; ++i) {
        const WideBvhNode n = random_node();
        Ray rays[kMaxPacket];
        Real t_max[kMaxPacket];
        const int count = 1 + static_cast<int>(rng() % kMaxPacket);
        for (int r = 0; r < count; ++r) rays[r] = random_ray(n), t_max[r] = limits[rng() % 5];
        // The scalar reference: SlabRay::clip's operations, per ray and lane.
        unsigned expected_mask[kMaxPacket] = {};
        Real expected_near[kMaxPacket][kBvhWidth];
        for (int r = 0; r < count; ++r) {
            const SlabRay slab(rays[r]);
            for (int k = 0; k < kBvhWidth; ++k) {
                Real t_in = 0, t_out = kInfinity;
                for (int a = 0; a < 3; ++a) {
                    const Real t0 = (n.box[a][0][k] - slab.origin[a]) * slab.inverse_direction[a];
                    const Real t1 = (n.box[a][1][k] - slab.origin[a]) * slab.inverse_direction[a];
                    t_in = std::max(t_in, std::min(t0, t1));
                    t_out = std::min(t_out, std::max(t0, t1));
                }
                expected_near[r][k] = t_in;
                // An empty lane (lo = +∞, hi = −∞) is never met (traverse_packet skips it).
                if (n.child[k] != kEmptyChild && t_in <= std::min(t_out * kSlabWiden, t_max[r]))
                    expected_mask[r] |= 1u << k;
            }
            met += __builtin_popcount(expected_mask[r]), lanes += kBvhWidth;
        }
        for (const Kernel kernel : kernels) {
            // A single ray's node test: AVX2's in the AVX-512 kernel too.
            const bool wide_lanes = kernel != Kernel::sse;
            for (int r = 0; r < count; ++r) {
                const WideRay wide(rays[r]);
                Real t_near[kBvhWidth];
                const unsigned mask = wide_lanes ? enter_avx2(wide, n, t_max[r], t_near)
                                                 : wide.enter_sse(n, t_max[r], t_near);
                ASSERT_EQ(mask, expected_mask[r]) << name_of(kernel) << " node " << i;
                for (int k = 0; k < kBvhWidth; ++k) {
                    if ((mask >> k) & 1) {
                        ASSERT_EQ(t_near[k], expected_near[r][k]) << name_of(kernel);
                    }
                }
            }
            const PacketRays packet(rays, count, t_max);
            const PacketRays::Mask active = packet.all & static_cast<PacketRays::Mask>(rng());
            for (int k = 0; k < kBvhWidth; ++k) {
                if (n.child[k] == kEmptyChild) continue;
                Real t = kInfinity, expected_t = kInfinity;
                PacketRays::Mask expected = 0;
                for (int r = 0; r < count; ++r)
                    if ((active >> r) & 1 && (expected_mask[r] >> k) & 1)
                        expected |= 1u << r, expected_t = std::min(expected_t, expected_near[r][k]);
                const auto enter = [&] {
                    switch (kernel) {
                    case Kernel::avx512:
                        return enter_avx512(packet, n, k, active, t);
                    case Kernel::avx2:
                        return enter_avx2(packet, n, k, active, t);
                    case Kernel::sse:
                        break;
                    }
                    return packet.enter_sse(n, k, active, t);
                };
                ASSERT_EQ(enter(), expected) << name_of(kernel);
                ASSERT_EQ(t, expected_t) << name_of(kernel);
            }
        }
    }
    EXPECT_GT(met, lanes / 20) << "too few boxes met to mean much"; // about 7% are
    EXPECT_LT(met, lanes * 9 / 10) << "too few boxes missed to mean much";
}

// sphere_roots4 (four spheres placed by an offset and a uniform scale, against one ray)
// against sphere_roots on the ray each sphere's Transform::to_object gives, lane by lane, bit for
// bit: rays through the centre, tangent (grazing), from inside, axis-parallel, and missing;
// radii from 1e-4 to 1e4, centres up to 1e5 from the origin; identity and translation too
// (inverse scale 1). Two million lane tests in Release.
TEST(Kernel, SphereBlocksAgreeExactlyWithTheSingleTest) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(-1, 1);
    static constexpr float kRadii[] = {1e-4f, 1e-2f, 1, 1, 1e2f, 1e4f};
    const int blocks = testing::kUnderSanitizers ? 25000 : 250000;
    std::uint64_t hits = 0, tests = 0;
    for (int b = 0; b < blocks; ++b) {
        Real x[4], y[4], z[4], inverse_scale[4];
        Transform placed[4];
        for (int i = 0; i < 4; ++i) {
            const double radius = kRadii[rng() % 6];
            const DVec3 centre =
                DVec3(u(rng), u(rng), u(rng)) * (rng() % 3 == 0 ? 1e5 : 10.0 * radius);
            const int kind = static_cast<int>(rng() % 4);
            // An identity may store its offset as −0 (as_offset_scale must not subtract it).
            DMat4 identity(1.0);
            if (rng() % 2) identity[3] = glm::dvec4(-0.0, -0.0, -0.0, 1.0);
            const DMat4 m = kind == 0   ? identity
                            : kind == 1 ? translation_matrix(centre)
                                        : translation_matrix(centre) * scale_matrix(DVec3(radius));
            placed[i] = make_transform(m);
            Vec3 offset;
            ASSERT_TRUE(placed[i].as_offset_scale(offset, inverse_scale[i]));
            x[i] = offset.x, y[i] = offset.y, z[i] = offset.z;
        }
        for (int r = 0; r < 8; ++r) {
            // Aimed at one sphere: through its centre, tangent to it, or nearby; from outside or
            // from inside it.
            const Transform& at = placed[rng() % 4];
            const Vec3 centre = at.offset;
            const Real radius = at.kind == TransformClass::uniform_scale ? at.scale : 1;
            Vec3 direction(u(rng), u(rng), u(rng));
            if (rng() % 4 == 0) direction = Vec3(0), direction[rng() % 3] = 1;
            if (direction == Vec3(0.0f)) direction = {1, 0, 0};
            const Vec3 side = glm::normalize(glm::cross(direction, Vec3(0.3f, 0.5f, 0.7f)));
            Vec3 origin = centre - 3.0f * radius * glm::normalize(direction);
            switch (rng() % 4) {
            case 0: // tangent
                origin += radius * side;
                break;
            case 1: // from inside
                origin = centre + 0.5f * radius * Vec3(u(rng), u(rng), u(rng));
                break;
            case 2:
                origin += 2.0f * radius * u(rng) * side;
                break;
            default:
                break;
            }
            if (rng() % 8 == 0) origin.x = -0.0f; // a −0 coordinate: kept by an identity
            const Ray ray{origin, direction};
            SphereRoots got[4];
            sphere_roots4(ray, x, y, z, inverse_scale, got);
            for (int i = 0; i < 4; ++i) {
                const SphereRoots expected = sphere_roots(placed[i].to_object(ray));
                ASSERT_EQ(got[i].missed, expected.missed) << "block " << b << " lane " << i;
                if (expected.missed) continue;
                ASSERT_EQ(std::bit_cast<std::uint32_t>(got[i].t0),
                          std::bit_cast<std::uint32_t>(expected.t0))
                    << "block " << b << " lane " << i;
                ASSERT_EQ(std::bit_cast<std::uint32_t>(got[i].t1),
                          std::bit_cast<std::uint32_t>(expected.t1))
                    << "block " << b << " lane " << i;
                ++tests, hits += sphere_hit(expected, kInfinity).found();
            }
        }
    }
    EXPECT_GT(hits, tests / 4) << "too few hits to mean much";
}

// Bits equal, any NaN equal to any NaN (which NaN a division of zeros gives is the processor's).
bool same_bits(Real a, Real b) {
    return (std::isnan(a) && std::isnan(b)) ||
           std::bit_cast<std::uint32_t>(static_cast<float>(a)) ==
               std::bit_cast<std::uint32_t>(static_cast<float>(b));
}

// A random placement of one of every kind: an identity (its offset sometimes −0), a translation
// up to 1e5 away, a uniform scale from 1e-4 to 1e4, or general: rotated and scaled unevenly
// (one axis squashed up to a millionfold) or sheared.
Transform random_placement(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    static constexpr double kScales[] = {1e-4, 1e-2, 1, 1, 1e2, 1e4};
    const double scale = kScales[rng() % 6];
    const DVec3 where = DVec3(u(rng), u(rng), u(rng)) * (rng() % 3 == 0 ? 1e5 : 10.0 * scale);
    DMat4 m(1.0);
    switch (rng() % 4) {
    case 0:
        if (rng() % 2) m[3] = glm::dvec4(-0.0, -0.0, -0.0, 1.0);
        break;
    case 1:
        m = translation_matrix(where);
        break;
    case 2:
        m = translation_matrix(where) * scale_matrix(DVec3(scale));
        break;
    default: {
        DMat4 linear = scale_matrix(DVec3(scale * (0.2 + std::abs(u(rng))),
                                          scale * (rng() % 4 == 0 ? 1e-6 : 0.2 + std::abs(u(rng))),
                                          scale * (0.2 + std::abs(u(rng)))));
        if (rng() % 3 == 0)
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) linear[c][r] += c == r ? 0.0 : 0.5 * scale * u(rng);
        m = translation_matrix(where) *
            rotation_matrix({u(rng), u(rng), u(rng) + 0.1}, 180 * u(rng)) * linear;
        if (why_unusable(m)) m = translation_matrix(where);
    }
    }
    return make_transform(m);
}

// ToObjectColumns::to_object4 against each Transform::to_object, and cylinder_crossings4 against
// cylinder_crossings on that ray, lane by lane, bit for bit: placements of every kind, from any
// slot (reading into the padding), and rays aimed at one of the four cylinders' sides, cap
// rims and cap centres, tangent to the side, along the axis (no side quadratic), from inside,
// axis-parallel in world space, and with −0 coordinates. 480,000 rays, each on up to four
// placements, in Release.
TEST(Kernel, LeafLanesTakeRaysToObjectSpaceAndCrossCylindersExactlyAsTheSingleCode) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    const int blocks = testing::kUnderSanitizers ? 6000 : 60000;
    std::uint64_t lanes = 0, side_hits = 0, cap_hits = 0;
    for (int b = 0; b < blocks; ++b) {
        const std::size_t slots = 1 + rng() % 4;
        Transform placed[4];
        ToObjectColumns columns;
        columns.assign(slots);
        for (std::size_t i = 0; i < slots; ++i)
            placed[i] = random_placement(rng), columns.set(i, placed[i]);
        for (int r = 0; r < 8; ++r) {
            const Transform& at = placed[rng() % slots];
            const auto to_world = [&](DVec3 p) {
                return DVec3(glm::dmat3(at.linear) * p + DVec3(at.offset));
            };
            const double angle = 3.14159265358979 * u(rng);
            const DVec3 rim(std::cos(angle), 0, std::sin(angle));
            DVec3 target, along(u(rng), u(rng), u(rng));
            switch (rng() % 5) {
            case 0: // the side, or just past its ends
                target = rim + DVec3(0, 0.5 + 0.7 * u(rng), 0);
                break;
            case 1: // tangent to the side
                target = rim + DVec3(0, 0.5 + 0.5 * u(rng), 0);
                along = glm::cross(rim, DVec3(0, 1, 0)) + DVec3(0, 0.1 * u(rng), 0);
                break;
            case 2: // a cap's rim
                target = rim + DVec3(0, rng() % 2, 0);
                break;
            case 3: // along the axis
                target = DVec3(0.9 * u(rng), 0.5, 0.9 * u(rng)), along = DVec3(0, 1, 0);
                break;
            default: // a cap's centre
                target = DVec3(0, rng() % 2, 0);
                break;
            }
            const Vec3 world_target(to_world(target));
            Vec3 direction(glm::normalize(glm::dmat3(at.linear) * along));
            if (rng() % 4 == 0) direction = Vec3(0), direction[rng() % 3] = rng() % 2 ? 1 : -1;
            if (!(glm::length(direction) > 0)) direction = {0, 0, 1};
            const float reach = glm::length(Vec3(to_world(DVec3(1, 1, 1)) - to_world(DVec3(0))));
            Vec3 origin = rng() % 4 == 0 ? Vec3(to_world(DVec3(0.3 * u(rng), 0.5, 0.3 * u(rng))))
                                         : world_target - 3.0f * reach * direction;
            if (rng() % 8 == 0) origin[rng() % 3] = -0.0f;
            const Ray ray{origin, direction};

            const std::size_t first = rng() % slots;
            Rays4 got;
            columns.to_object4(ray, first, got);
            CylinderCrossings crossed[4];
            cylinder_crossings4(got, crossed);
            for (std::size_t i = 0; first + i < slots; ++i) {
                const Ray expected = placed[first + i].to_object(ray);
                const Ray lane = got.lane(static_cast<int>(i));
                for (int axis = 0; axis < 3; ++axis) {
                    ASSERT_TRUE(same_bits(lane.origin[axis], expected.origin[axis]))
                        << "block " << b << " lane " << i << " origin " << axis;
                    ASSERT_TRUE(same_bits(lane.direction[axis], expected.direction[axis]))
                        << "block " << b << " lane " << i << " direction " << axis;
                }
                const CylinderCrossings want = cylinder_crossings(expected, false);
                for (int k = 0; k < 4; ++k)
                    ASSERT_TRUE(same_bits(crossed[i].t[k], want.t[k]))
                        << "block " << b << " lane " << i << " crossing " << k << ": got "
                        << crossed[i].t[k] << ", expected " << want.t[k];
                const ShapeHit hit = cylinder_hit(want, kInfinity, false);
                ++lanes, side_hits += hit.found() && hit.part == 0,
                    cap_hits += hit.found() && hit.part != 0;
            }
        }
    }
    EXPECT_GT(side_hits, lanes / 10) << "too few side hits to mean much";
    EXPECT_GT(cap_hits, lanes / 20) << "too few cap hits to mean much";
}

} // namespace
} // namespace glint
