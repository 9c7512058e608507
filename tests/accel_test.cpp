// Every acceleration structure returns exactly the brute-force list's answers: the same closest
// object, the same t to the bit, the same any-hit verdicts, on random scenes built to be hard
// (thin and sheared transforms, duplicates that tie, coplanar flat sets, axis-parallel rays),
// and renders that are byte-identical.
#include "test_scenes.h"

#include "trace/render.h"

#include <gtest/gtest.h>

#include <random>

namespace glint {
namespace {

// A random scene of `count` objects of every shape. Variants stress the structures' corners.
Scene random_scene(unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
    Scene scene = parse_scene(
        R"({"camera": {"eye": [0, 0, 12], "look_at": [0, 0, 0], "width": 8, "height": 8}})",
        "random.json");
    const int variant = static_cast<int>(seed % 4);
    TriangleMesh mesh;
    for (int k = 0; k < 30; ++k) mesh.vertices.push_back(glm::vec3(u(rng), u(rng), u(rng)));
    for (std::uint32_t k = 0; k + 2 < 30; k += 3) mesh.triangles.push_back({k, k + 1, k + 2});
    scene.meshes.push_back(mesh);
    if (seed % 5 == 0)
        scene.objects.push_back(
            {ShapeKind::plane, 0, rotation_matrix({u(rng), 1, u(rng)}, 30 * u(rng)), 0, 0});
    for (int i = 0; i < count; ++i) {
        SceneObject o;
        o.shape = static_cast<ShapeKind>(rng() % 8);
        if (o.shape == ShapeKind::plane) o.shape = ShapeKind::box;
        o.top_radius = static_cast<float>(pos(rng) * (rng() % 2));
        DMat4 linear(1.0);
        if (variant == 1) { // thin: one axis squashed a thousandfold
            linear = scale_matrix({0.5 + pos(rng), 1e-3, 0.5 + pos(rng)});
        } else if (variant == 2) { // sheared
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) linear[c][r] = (c == r ? 0.8 : 0.0) + 0.3 * u(rng);
        } else {
            linear = scale_matrix({0.2 + pos(rng), 0.2 + pos(rng), 0.2 + pos(rng)});
        }
        const DMat4 rotation =
            variant == 3 ? DMat4(1.0) : rotation_matrix({u(rng), u(rng), 1}, 180 * u(rng));
        // Variant 3: axis-aligned and on a coarse lattice, so faces share planes and boxes touch.
        const DVec3 where = variant == 3 ? DVec3(std::round(4 * u(rng)), std::round(4 * u(rng)),
                                                 std::round(4 * u(rng)))
                                         : DVec3(5 * u(rng), 5 * u(rng), 5 * u(rng));
        o.transform = translation_matrix(where) * rotation * linear;
        if (why_unusable(o.transform)) o.transform = translation_matrix(where);
        // Two spheres in three placed without rotation or shear (scaled uniformly, or only
        // moved), as SPD's are: a BVH leaf tests those four at a time (sphere_roots4). On the
        // lattice they touch, and duplicates tie.
        if (o.shape == ShapeKind::sphere && i % 3 != 2 && (variant == 0 || variant == 3))
            o.transform = translation_matrix(where) *
                          (i % 3 == 0 ? scale_matrix(DVec3(0.3 + 0.1 * std::abs(where.x)))
                                      : DMat4(1.0));
        scene.objects.push_back(o);
        if (rng() % 10 == 0) scene.objects.push_back(o); // an exact duplicate: every hit ties
    }
    return scene;
}

Ray random_ray(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    Vec3 origin(7 * u(rng), 7 * u(rng), 7 * u(rng));
    Vec3 direction(u(rng), u(rng), u(rng));
    switch (rng() % 6) {
    case 0:
        direction = {0, 0, u(rng) < 0 ? -1.0f : 1.0f};
        break; // axis-parallel: 1/d = ±inf
    case 1:
        direction.y = 0;
        break; // parallel to a coordinate plane
    case 2:
        origin = {std::round(origin.x), std::round(origin.y), origin.z};
        break; // on lattice planes
    default:
        break;
    }
    if (direction == Vec3(0.0f)) direction = {1, 0, 0};
    return {origin, direction};
}

// Every third object of a random scene glass (a second material that transmits half), for the
// queries that ask for opaque objects alone.
void make_every_third_glass(Scene& scene) {
    scene.materials.push_back(scene.materials[0]);
    scene.materials.back().transmission = 0.5f;
    for (std::size_t i = 0; i < scene.objects.size(); i += 3) scene.objects[i].material = 1;
}

// What the list answers a packet's rays one at a time.
struct ListAnswers {
    Hit hit, skipped; // intersect, without skips and with `closest_skips`
    bool occluded = false, opaque = false, glass = false;
};

// A packet's four queries on `tested` (intersect_packet without skips and with
// `closest_skips`, occluded_packet and opaque_between_packet with `skips`): each ray's answers
// must be the list's ray by ray, t, part and u, v included; whether glass lies on the ray is
// asked only where nothing opaque does. The list's answers in `answers`.
void expect_packet_agrees(const World& tested, const World& list, std::span<const Ray> batch,
                          const std::uint32_t* closest_skips, const std::uint32_t* skips,
                          float t_max, const std::string& where, ListAnswers* answers) {
    const std::size_t count = batch.size();
    Hit hits[kMaxPacket], skipping[kMaxPacket];
    bool blocked[kMaxPacket], opaque[kMaxPacket], glass[kMaxPacket];
    tested.intersect_packet(batch, hits);
    tested.intersect_packet(batch, skipping, closest_skips);
    tested.occluded_packet(batch, t_max, skips, blocked);
    tested.opaque_between_packet(batch, t_max, skips, opaque, glass);
    const auto same = [&](const Hit& got, const Hit& expected, std::size_t r, const char* query) {
        const std::string at = where + " ray " + std::to_string(r) + " " + query;
        ASSERT_EQ(got.object, expected.object) << at;
        ASSERT_EQ(got.t, expected.t) << at;
        ASSERT_EQ(got.primitive, expected.primitive) << at;
        ASSERT_EQ(got.u, expected.u) << at;
        ASSERT_EQ(got.v, expected.v) << at;
    };
    for (std::size_t r = 0; r < count; ++r) {
        ListAnswers& a = answers[r];
        a.hit = list.intersect(batch[r]);
        a.skipped = list.intersect(batch[r], kInfinity, closest_skips[r]);
        a.occluded = list.occluded(batch[r], t_max, skips[r]);
        a.opaque = list.opaque_between(batch[r], t_max, skips[r], a.glass);
        ASSERT_NO_FATAL_FAILURE(same(hits[r], a.hit, r, "closest"));
        ASSERT_NO_FATAL_FAILURE(same(skipping[r], a.skipped, r, "closest, skipping"));
        ASSERT_EQ(blocked[r], a.occluded) << where << " ray " << r << " any";
        ASSERT_EQ(opaque[r], a.opaque) << where << " ray " << r << " opaque";
        if (!opaque[r]) {
            ASSERT_EQ(glass[r], a.glass) << where << " ray " << r << " glass";
        }
    }
}

class AccelTest : public ::testing::TestWithParam<AccelKind> {};

TEST_P(AccelTest, AgreesExactlyWithTheListOnAMillionRandomRays) {
    const AccelKind kind = GetParam();
    std::mt19937 rng(1234);
    std::uint64_t rays = 0, hits = 0;
    // Under the sanitizers (test_scenes.h), every scene but a quarter of the rays.
    constexpr int kRaysPerScene = testing::kUnderSanitizers ? 1000 : 4000;
    for (unsigned seed = 0; seed < 250; ++seed) {
        Scene scene = random_scene(seed, 10 + static_cast<int>(seed % 7) * 15);
        scene.camera.eye = {0, 0, 0};
        scene.camera.look_at = {0, 0, -1};
        make_every_third_glass(scene);
        const World list(scene, AccelKind::list);
        const World other(scene, kind);
        for (int k = 0; k < kRaysPerScene; ++k, ++rays) {
            const Ray ray = random_ray(rng);
            const Hit expected = list.intersect(ray);
            const Hit got = other.intersect(ray);
            hits += expected.found();
            ASSERT_EQ(got.object, expected.object)
                << name_of(kind) << " scene " << seed << " ray " << k;
            ASSERT_EQ(got.t, expected.t) << name_of(kind) << " scene " << seed << " ray " << k;
            ASSERT_EQ(got.primitive, expected.primitive) << name_of(kind) << " scene " << seed;
            // Any-hit, up to half and twice the closest distance (or a random one on a miss).
            const float t_max = expected.found() ? expected.t * (k % 2 ? 0.5f : 2.0f) : 20.0f;
            ASSERT_EQ(other.occluded(ray, t_max), list.occluded(ray, t_max))
                << name_of(kind) << " scene " << seed;
            // The same for opaque objects alone (a third of them are glass), and whether glass
            // lies on the way where nothing opaque does.
            bool glass = false, list_glass = false;
            const bool opaque = other.opaque_between(ray, t_max, kNoObject, glass);
            ASSERT_EQ(opaque, list.opaque_between(ray, t_max, kNoObject, list_glass))
                << name_of(kind) << " scene " << seed << " ray " << k;
            if (!opaque) {
                ASSERT_EQ(glass, list_glass) << name_of(kind) << " scene " << seed;
            }
        }
    }
    EXPECT_EQ(rays, 250u * kRaysPerScene);
    EXPECT_GT(hits, rays / 10) << "too few hits to mean much";
}

// Packets (World::intersect_packet without skips and with them, occluded_packet,
// opaque_between_packet): every ray of a packet gets exactly the list's answer, for coherent
// packets (a 4×4 block of camera rays, shadow rays from scattered points towards one light) and
// incoherent ones (random rays, as reflections off curved surfaces), partly filled ones
// included: about a million rays in 125,000 packets over 250 scenes for the BVH, in which a
// third of the objects are glass (for opaque_between). The closest-hit packets with skips skip,
// for every other ray, the object it would hit first (as a reflected ray skips the surface it
// leaves, which it would otherwise meet at t ≈ 0).
TEST_P(AccelTest, PacketsAgreeExactlyWithTheListRayByRay) {
    const AccelKind kind = GetParam();
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uint64_t rays = 0, glass_rays = 0, skipped_hits = 0;
    // The eight-wide BVH traverses packets; the other structures answer them ray by ray. Under the
    // sanitizers (test_scenes.h), fewer scenes.
    const unsigned scenes = kind == AccelKind::bvh ? (testing::kUnderSanitizers ? 50 : 250)
                                                   : (testing::kUnderSanitizers ? 10 : 20);
    for (unsigned seed = 0; seed < scenes; ++seed) {
        Scene scene = random_scene(seed, 10 + static_cast<int>(seed % 7) * 15);
        scene.camera.eye = {0, 0, 0};
        scene.camera.look_at = {0, 0, -1};
        make_every_third_glass(scene);
        const World list(scene, AccelKind::list);
        const World other(scene, kind);
        for (int packet = 0; packet < 500; ++packet) {
            const std::size_t count = 1 + rng() % kMaxPacket;
            Ray batch[kMaxPacket];
            std::uint32_t skips[kMaxPacket];
            const Vec3 light(7 * u(rng), 7 * u(rng), 7 * u(rng));
            const Vec3 eye(7 * u(rng), 7 * u(rng), 7 * u(rng));
            for (std::size_t r = 0; r < count; ++r) {
                switch (packet % 3) {
                case 0: // camera rays through a small block
                    batch[r] = {eye, Vec3(-eye.x + 0.05f * static_cast<float>(r % 4),
                                          -eye.y + 0.05f * static_cast<float>(r / 4), -eye.z)};
                    break;
                case 1: // towards one light from scattered points, as a tile's shadow rays
                    batch[r].origin = Vec3(5 * u(rng), 5 * u(rng), 5 * u(rng));
                    batch[r].direction = light - batch[r].origin;
                    break;
                default:
                    batch[r] = random_ray(rng);
                }
                if (batch[r].direction == Vec3(0.0f)) batch[r].direction = {0, 0, 1};
                skips[r] = rng() % 4 == 0 ? static_cast<std::uint32_t>(rng() % 20) : kNoObject;
            }
            std::uint32_t first_skipped[kMaxPacket];
            for (std::size_t r = 0; r < count; ++r)
                first_skipped[r] = r % 2 == 0 ? list.intersect(batch[r]).object : skips[r];
            const float t_max = packet % 3 == 1 ? 1.0f : 4 + 10 * (u(rng) + 1);
            ListAnswers answers[kMaxPacket];
            ASSERT_NO_FATAL_FAILURE(expect_packet_agrees(
                other, list, {batch, count}, first_skipped, skips, t_max,
                "scene " + std::to_string(seed) + " packet " + std::to_string(packet), answers));
            for (std::size_t r = 0; r < count; ++r, ++rays) {
                const ListAnswers& a = answers[r];
                skipped_hits += a.skipped.found() && a.skipped.object != a.hit.object;
                glass_rays += a.glass && !a.opaque;
            }
        }
    }
    EXPECT_GT(rays, scenes * 500 * 4);
    EXPECT_GT(glass_rays, rays / 100) << "too few rays through glass alone to mean much";
    EXPECT_GT(skipped_hits, rays / 100) << "too few hits beyond a skipped object to mean much";
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheList) {
    Scene scene = load_scene(GLINT_SOURCE_DIR "/scenes/default.json");
    scene.camera.width = 120, scene.camera.height = 90;
    EXPECT_EQ(render(World(scene, GetParam())).bytes().rgb,
              render(World(scene, AccelKind::list)).bytes().rgb);
    Scene crowd = random_scene(7, 300);
    crowd.camera.width = 96, crowd.camera.height = 72;
    crowd.lights.push_back({{5, 8, 6}, Vec3(1.0f)});
    crowd.materials[0].reflectivity = 0.5f;
    EXPECT_EQ(render(World(crowd, GetParam())).bytes().rgb,
              render(World(crowd, AccelKind::list)).bytes().rgb);
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheListAtTheEdgeOfTheCoordinateRange) {
    // Objects reaching ±1e15, the largest extent the loader accepts, beside unit spheres. Beyond
    // it (a 1e15 vertex scaled by 1e15, found while looking for overflow by hand) squared radii
    // overflow float and the sphere tree lost hits; the loader now refuses such objects.
    std::string objects;
    for (int i = 0; i < 20; ++i)
        objects += R"({"shape": "sphere", "transform": [{"translate": [)" + std::to_string(i) +
                   ", 0, " + std::to_string(-i) + "]}]},";
    const Scene scene =
        parse_scene(R"({"camera": {"width": 64, "height": 48, "eye": [0, 0, -9.9e14]},
        "lights": [{"position": [1e15, 1e15, 1e15]}], "objects": [)" +
                        objects + R"(
        {"shape": "mesh", "vertices": [[1e15, 0, 0], [0, 1e15, 0], [0, 0, -1e15]], "indices": [0, 1, 2]},
        {"shape": "sphere", "transform": [{"scale": 4e14}, {"translate": [5e14, 0, 0]}]},
        {"shape": "box", "transform": [{"scale": [1e15, 1e-3, 1e15]}, {"translate": [0, -3, 0]}]}]})",
                    "far.json");
    const RenderResult list = render(World(scene, AccelKind::list));
    EXPECT_GT(list.rays.shadow, list.rays.primary / 4) << "the scene should fill the image";
    EXPECT_EQ(render(World(scene, GetParam())).bytes().rgb, list.bytes().rgb);
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheListForAVeryElongatedScene) {
    // Found by fuzz/scene_fuzzer.cpp (fuzz/seeds/scene/elongated-cylinder.json): a cylinder
    // 3.5e14 long made the grid's cells-per-axis 1e10 before clamping, beyond int (undefined
    // behaviour, caught by UBSan in the sanitize build). Cell counts are now clamped in float.
    Scene scene = parse_scene(R"({"camera": {"eye": [0, 6, 7], "look_at": [0, 0.3, 0]},
        "lights": [{"position": [-3, 5, 2]}], "objects": [
        {"shape": "sphere", "transform": [{"scale": 0.6}, {"translate": [-1.2, 0.6, 0.6]}]},
        {"shape": "cylinder", "transform": [{"scale": [0.351e15, 1.6, 0.35]}, {"translate": [1.2, 0, 0.4]}]},
        {"shape": "box", "transform": [{"scale": [0.5, 0.25, 0.5]}, {"translate": [0, 0.25, -0.9]}]}]})",
                              "elongated.json");
    scene.camera.width = 48, scene.camera.height = 36;
    EXPECT_EQ(render(World(scene, GetParam())).bytes().rgb,
              render(World(scene, AccelKind::list)).bytes().rgb);
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheListForAnObjectThinnerThanFloatResolves) {
    // Found by fuzz/scene_fuzzer.cpp (fuzz/seeds/scene/flat-cone.json): a cone squashed to 1e-8
    // at 8 units from the eye, thinner than float's spacing there, so its object-space rays are
    // noise and it reported hits far outside its own box. The list tests that box first, the
    // hierarchies only larger ones, so their images differed. Hits now count only inside the
    // object's bounds, for every structure.
    Scene scene = parse_scene(R"({"camera": {"eye": [0, 1, 8], "look_at": [0, 0, 0]},
        "lights": [{"position": [4, 6, 5]}], "objects": [
        {"shape": "cone", "transform": [{"scale": [0.3, 1.028e-8, 0.3]},
         {"rotate": {"axis": [1, 1, 0], "degrees": 51}}, {"translate": [1, -2, -0.3]}]},
        {"shape": "sphere", "transform": [{"scale": 0.3}, {"translate": [-2, -2, 0]}]},
        {"shape": "box", "transform": [{"scale": 0.3}, {"translate": [2, 0, -1.6]}]},
        {"shape": "plane", "transform": [{"translate": [0, -2.5, 0]}]}]})",
                              "flat-cone.json");
    scene.camera.width = 48, scene.camera.height = 36;
    EXPECT_EQ(render(World(scene, GetParam())).bytes().rgb,
              render(World(scene, AccelKind::list)).bytes().rgb);
}

// A fuzz_nff seed rendered with `accel` and with the list, by default as the fuzzer renders it
// (12×9).
void expect_list_image(const char* seed, AccelKind accel, int width = 12, int height = 9) {
    Scene scene = load_scene(std::string(GLINT_SOURCE_DIR "/fuzz/seeds/nff/") + seed);
    scene.camera.width = width, scene.camera.height = height;
    EXPECT_EQ(render(World(scene, accel)).bytes().rgb,
              render(World(scene, AccelKind::list)).bytes().rgb);
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheListForARayLongerThanFloatResolvesItsLeaves) {
    // Found by fuzz/nff_fuzzer.cpp: the camera inside a sphere of radius 1e15 (9.99e14 since NFF
    // scenes meet the scene check's reach rule, io/scene_check.h, as JSON ones did), whose
    // reflections bounce 2e15 across it past spheres 0.15 in radius. At that distance the
    // crossings of neighbouring split planes round together, and the kd-tree, comparing them
    // exactly, skipped a leaf whose sphere the list hits. It now skips a child only when it is
    // beyond the segment by more than rounding.
    expect_list_image("kd-far-leaf.nff", GetParam());
}

TEST_P(AccelTest, TiesAtTheBestDistanceAreSeenWhateverTheVisitingOrder) {
    // Found by fuzz/nff_fuzzer.cpp (its sphere now 9.99e14 in radius, within the reach rule): a
    // reflected ray 1e15 long hits two tubes at the same float
    // distance. The list saw the lower index first; the BVH saw the other first and then pruned
    // the first tube's box, whose entry rounded a few ulps beyond that distance. Box tests
    // against the best distance now allow for rounding.
    expect_list_image("bvh-tie.nff", GetParam());
}

TEST_P(AccelTest, OverlappingCoplanarMeshesShowTheNearerWhateverTheVisitingOrder) {
    // Found by fuzz/nff_fuzzer.cpp in balls-1, minimised: two quads 24 across whose triangles
    // overlap in one plane, their distances a few ulps apart. The list tested the first mesh,
    // then pruned the second mesh's box (inside intersect_mesh) against that hit, and so missed
    // its nearer triangle, which the BVH, visiting the second mesh first, found. At 12×9 the
    // box was a few ulps beyond; at 120×90 one triangle's distance was 40 ulps before its box's
    // entry. Meshes now prune boxes loosely, and loose() allows for triangles' rounding.
    expect_list_image("coplanar-quads.nff", GetParam());
    expect_list_image("coplanar-quads.nff", GetParam(), 120, 90);
}

TEST_P(AccelTest, AHitJustOutsideAFlatBoxIsSeenWhateverTheVisitingOrder) {
    // Found by fuzz/nff_fuzzer.cpp (coplanar-quads.nff's kind, mutated): a transmitted ray
    // starts 0.0015 above two quads 24 across that nearly meet. One quad's triangle test put its
    // hit 2e-6 outside the mesh's own box (intersect_mesh's first test), flat and unpadded: its
    // t came 1e-3 before the box's entry, beyond loose()'s allowance. The list, meeting the
    // other quad first, pruned that box against its hit; the sphere tree and the binary BVH,
    // meeting it first, kept the nearer hit. A mesh's box and its triangles' boxes are now
    // padded by a few ulps of their largest coordinate on every axis (padded(), bounds.h).
    expect_list_image("near-quads.nff", GetParam());
}

TEST_P(AccelTest, AnOccluderAtTheFarEndOfAVeryLongShadowRayIsSeenByEveryStructure) {
    // Found by fuzz/nff_fuzzer.cpp, minimised: a point on a sphere of radius 2.3e9 casts its
    // shadow ray 2e9 long past a thin cone near the light, hit at t = 1 − 1 ulp. The list tested
    // the cone's box against t_max = 1 first, and its entry rounded beyond 1; the BVH checked
    // the same box after the hit, loosely, and counted the cone. Occlusion now tests boxes
    // loosely in every structure.
    expect_list_image("shadow-box-at-segment-end.nff", GetParam(), 12, 3);
}

TEST_P(AccelTest, RendersAreByteIdenticalToTheListWhereFloatBarelyResolvesTheGridsFaces) {
    // Found by fuzz/nff_fuzzer.cpp in an SPD tree, minimised: one cone's radius mutated to 2e7
    // stretches the grid to ±2e7, where float spaces coordinates 2 apart, and puts a cell face
    // through the tree's branches. The DDA's crossing of that face and the bins the branches
    // were listed in then disagreed by rounding, and the grid skipped a branch the list hits.
    // Items are now listed in every cell within a margin of their boxes.
    expect_list_image("grid-far-faces.nff", GetParam());
}

TEST_P(AccelTest, RaysFromFarBeyondTheSceneGetTheListsAnswers) {
    // Cast from 1e9 away, a ray's crossings of cells 0.1 wide are uncertain by far more than
    // a cell; the grid then tests every item rather than trust its DDA (grid.h).
    Scene scene =
        parse_scene(R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1]}})", "far.json");
    for (int i = 0; i < 64; ++i)
        scene.objects.push_back({ShapeKind::sphere, 0,
                                 translation_matrix({i % 8 * 0.3, i / 8 * 0.3, (i % 3) * 0.2}) *
                                     scale_matrix(DVec3(0.1)),
                                 0, 0});
    const World list(scene, AccelKind::list), other(scene, GetParam());
    for (int i = 0; i < 400; ++i) {
        const Vec3 target(0.05f * static_cast<float>(i % 20) - 0.1f,
                          0.05f * static_cast<float>(i / 20) - 0.1f, 0.1f);
        const Vec3 origin(1e9f, 3e8f * static_cast<float>(i % 3), 2e8f);
        const Ray ray{origin, glm::normalize(target - origin)};
        const Hit expected = list.intersect(ray), got = other.intersect(ray);
        EXPECT_EQ(got.object, expected.object) << "ray " << i;
        EXPECT_EQ(got.t, expected.t) << "ray " << i;
    }
}

TEST_P(AccelTest, HandlesEmptySingleAndDegenerateSets) {
    Scene scene =
        parse_scene(R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1]}})", "empty.json");
    EXPECT_FALSE(World(scene, GetParam()).intersect({Vec3(0.0f), {0, 0, -1}}).found());
    scene.objects.push_back({ShapeKind::sphere, 0, translation_matrix({0, 0, -5}), 0, 0});
    EXPECT_EQ(World(scene, GetParam()).intersect({Vec3(0.0f), {0, 0, -1}}).t, 4.0f);
    // 50 identical spheres: every ray ties 50 ways, the lowest index must win.
    for (int i = 0; i < 49; ++i) scene.objects.push_back(scene.objects[0]);
    EXPECT_EQ(World(scene, GetParam()).intersect({Vec3(0.0f), {0, 0, -1}}).object, 0u);
    // A flat set: 60 disks in one plane (bounds of zero thickness).
    Scene flat =
        parse_scene(R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1]}})", "flat.json");
    for (int i = 0; i < 60; ++i)
        flat.objects.push_back(
            {ShapeKind::disk, 0,
             translation_matrix({i % 10 - 4.5, -2, -(i / 10) - 2.0}) * scale_matrix(DVec3(0.4)), 0,
             0});
    const World list(flat, AccelKind::list), other(flat, GetParam());
    for (int i = 0; i < 200; ++i) {
        const Ray ray{Vec3(0.0f), glm::normalize(Vec3(-0.9f + 0.009f * i, -0.3f, -1.0f))};
        EXPECT_EQ(other.intersect(ray).object, list.intersect(ray).object);
    }
}

constexpr auto kStructures = all_values<AccelKind>();
INSTANTIATE_TEST_SUITE_P(EveryStructure, AccelTest,
                         // Every structure but the list itself.
                         ::testing::ValuesIn(kStructures.begin() + 1, kStructures.end()),
                         [](const auto& info) { return std::string(name_of(info.param)); });

int depth_below(const BinaryBvh& bvh, std::uint32_t node) {
    const BvhNode& n = bvh.nodes()[node];
    if (n.count > 0) return 1;
    return 1 + std::max(depth_below(bvh, n.first), depth_below(bvh, n.first + 1));
}

TEST(Accel, BvhDepthStaysWithinTheTraversalStackWhereSahPeelsOneObjectALevel) {
    // Boxes at 2^-5k along x, then along y, then along z, each 0.3 of its distance wide: every
    // level's binned SAH finds one box alone in its top bin and splits it off: SAH alone built
    // 73 levels from these 84 boxes. Tiny ranges also made bin indices NaN before bin_index.
    std::vector<Bounds> boxes;
    for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 28; ++k) {
            Vec3 centre(0.0f);
            centre[axis] = std::exp2(-5.0f * static_cast<float>(k));
            const float r = 0.3f * centre[axis];
            boxes.push_back({centre - r, centre + r});
        }
    const BinaryBvh bvh(boxes);
    const int depth = depth_below(bvh, 0);
    EXPECT_LE(depth, kMaxBvhDepth);
    EXPECT_GT(depth, kSahDepth) << "no longer the adversarial case this test is about";
}

// kObjectLeaves lets the SAH choose every leaf of a scene's objects, a level costing half an
// object's test: eight boxes far apart each get a leaf of their own (leaves of up to four were
// forced until round three), and two that nearly coincide share one, which only the level's
// cost decides. A mesh's leaf of one block (kTriangleLeaves) is never split, and up to three
// blocks may share a leaf.
TEST(Accel, TheSahChoosesObjectLeavesAndAMeshBlockStaysWhole) {
    const auto leaf_sizes = [](const BinaryBvh& bvh) {
        std::vector<std::uint32_t> sizes;
        for (const BvhNode& n : bvh.nodes())
            if (n.count > 0) sizes.push_back(n.count);
        return sizes;
    };
    std::vector<Bounds> apart;
    for (int i = 0; i < 8; ++i) {
        const float x = 10.0f * static_cast<float>(i);
        apart.push_back({Vec3(x, 0.0f, 0.0f), Vec3(x + 1.0f, 1.0f, 1.0f)});
    }
    EXPECT_EQ(leaf_sizes(BinaryBvh(apart)), std::vector<std::uint32_t>(8, 1));

    const std::vector<Bounds> coinciding = {{Vec3(0.0f), Vec3(1.0f)}, {Vec3(0.01f), Vec3(1.01f)}};
    EXPECT_EQ(leaf_sizes(BinaryBvh(coinciding)), std::vector<std::uint32_t>{2});
    EXPECT_EQ(leaf_sizes(BinaryBvh(coinciding, {1, 0.0f})), std::vector<std::uint32_t>(2, 1))
        << "without the level's cost, the split is cheaper: the first case tests the cost";

    apart.resize(4);
    EXPECT_EQ(leaf_sizes(BinaryBvh(apart, kTriangleLeaves)), std::vector<std::uint32_t>{4});

    // A strip of unit boxes side by side, as a mesh's triangles are: twelve are one leaf of
    // three blocks (a level costs two block tests), thirteen more than a leaf holds.
    std::vector<Bounds> strip;
    for (int i = 0; i < 13; ++i) {
        const float x = static_cast<float>(i);
        strip.push_back({Vec3(x, 0.0f, 0.0f), Vec3(x + 1.0f, 1.0f, 1.0f)});
    }
    EXPECT_GT(leaf_sizes(BinaryBvh(strip, kTriangleLeaves)).size(), 1u);
    strip.resize(12);
    EXPECT_EQ(leaf_sizes(BinaryBvh(strip, kTriangleLeaves)), std::vector<std::uint32_t>{12});
    EXPECT_GT(leaf_sizes(BinaryBvh(strip, {kTriangleLanes, 0, 12})).size(), 1u)
        << "without the level's cost the strip is split: the case tests the cost";
}

// A mesh's own BVH (eight-wide, triangles in blocks in leaf order) returns exactly what testing every
// triangle in index order returns: the nearest t, and on equal t the lower triangle index, so
// the answer does not depend on the order the tree offers its leaves in. The mesh is a grid of
// triangles sharing edges and vertices (rays aimed at them tie on t), with a few triangles
// repeated at far-apart indices (every hit on them ties).
// A bumpy n × n grid of vertices 1 apart over x and z (y from 0 to 1.2), two triangles a cell,
// with repeats that tie: the same corners at a later index, and one at an earlier index too.
constexpr std::uint32_t kGrid = 24;
TriangleMesh grid_mesh() {
    TriangleMesh given;
    constexpr std::uint32_t n = kGrid;
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i)
            given.vertices.push_back({static_cast<float>(i), 0.3f * static_cast<float>((i * j) % 5),
                                      static_cast<float>(j)});
    for (std::uint32_t j = 0; j + 1 < n; ++j)
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
            const std::uint32_t a = j * n + i;
            given.triangles.push_back({a, a + n, a + 1});
            given.triangles.push_back({a + 1, a + n, a + n + 1});
        }
    for (const std::size_t k : {3u, 200u, 777u}) given.triangles.push_back(given.triangles[k]);
    given.triangles.insert(given.triangles.begin() + 5, given.triangles[900]);
    return given;
}

// The ways a test aims a packet's rays at the grid mesh.
enum class AtGrid { cell, vertex, edge_midpoint, camera_block, shadow, grazing };

// Ray r of a packet at the grid placed by `to_world` (its object space to the world): from
// `eye` towards a random point of it (a height of five levels, 0 to 1.2) in a cell, at a vertex
// or an edge's midpoint, or ray r of a 4×4 block towards its middle; from such a point towards
// `eye` (a shadow ray); or grazing along its cells in its object space.
template <class ToWorld>
Ray grid_ray(AtGrid at, std::size_t r, Vec3 eye, const ToWorld& to_world, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1), cell(0, static_cast<float>(kGrid - 1));
    Vec3 target(cell(rng), 0.3f * static_cast<float>(rng() % 5), cell(rng));
    switch (at) {
    case AtGrid::vertex:
        target = glm::round(target);
        break;
    case AtGrid::edge_midpoint:
        target.x = std::round(target.x * 2) / 2, target.z = std::round(target.z);
        break;
    case AtGrid::camera_block:
        target = Vec3(12 + 0.3f * static_cast<float>(r % 4), 0.5f,
                      12 + 0.3f * static_cast<float>(r / 4));
        break;
    case AtGrid::shadow: {
        const Vec3 from = to_world(target + Vec3(0, 0.01f, 0));
        return Ray{from, eye - from};
    }
    case AtGrid::grazing: {
        const Vec3 from = to_world({-1, target.y, target.z});
        const Vec3 to(static_cast<float>(kGrid), target.y, target.z + 0.01f * u(rng));
        return Ray{from, to_world(to) - from};
    }
    case AtGrid::cell:
        break;
    }
    return Ray{eye, to_world(target) - eye};
}

TEST(Accel, MeshHitsAreTheSameWhateverTheVisitingOrder) {
    constexpr std::uint32_t n = kGrid;
    const Mesh mesh = prepare_mesh(grid_mesh());
    ASSERT_FALSE(mesh.bvh.nodes().empty());

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0, static_cast<float>(n - 1));
    int ties = 0;
    for (int k = 0; k < 50000; ++k) {
        // From above, at a random point or exactly at a grid vertex or edge midpoint.
        Vec3 target(u(rng), 0, u(rng));
        if (k % 3 == 0) target = glm::round(target);
        if (k % 3 == 1) target.x = std::round(target.x * 2) / 2;
        const Vec3 origin(u(rng), 10, u(rng));
        const Ray ray{origin, target - origin};
        ShapeHit expected;
        const WatertightRay prepared(ray);
        for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
            const glm::uvec3 t = mesh.triangles[i];
            const TriangleHit h = intersect_triangle(mesh.vertices[t.x], mesh.vertices[t.y],
                                                     mesh.vertices[t.z], prepared);
            ties += h.t > 0 && h.t == expected.t;
            if (h.t > 0 && h.t < kInfinity && h.t < expected.t) expected = {h.t, i, h.u, h.v};
        }
        NoCounters none;
        const ShapeHit got = intersect_mesh(mesh, ray, kInfinity, none);
        ASSERT_EQ(got.t, expected.t) << "ray " << k;
        ASSERT_EQ(got.part, expected.part) << "ray " << k;
        ASSERT_EQ(got.u, expected.u) << "ray " << k;
        ASSERT_EQ(got.v, expected.v) << "ray " << k;
    }
    EXPECT_GT(ties, 1000) << "too few ties to mean much";
}

// A shadow ray's question of a mesh (Wanted::any) is answered at the first leaf holding a hit:
// found exactly when the nearest hit is, and then a true hit (its triangle's own test gives it,
// bit for bit) in (0, t_max), no nearer than the nearest. A soup of 2,000 random triangles in a
// unit cube, so that rays cross several; limits infinite, random, and exactly at the nearest
// hit (which is then outside the open interval: neither may find it).
TEST(Accel, MeshAnyHitIsFoundExactlyWhenTheNearestIs) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0, 1), wide(-2, 3);
    TriangleMesh soup;
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const Vec3 centre(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) {
            const Vec3 corner = centre + 0.15f * Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
            soup.vertices.push_back(glm::vec3(corner));
        }
        soup.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    const Mesh mesh = prepare_mesh(soup);
    ASSERT_FALSE(mesh.bvh.nodes().empty());
    int found = 0, farther = 0;
    for (int k = 0; k < 50000; ++k) {
        const Vec3 origin(wide(rng), wide(rng), wide(rng));
        const Ray ray{origin, Vec3(u(rng), u(rng), u(rng)) - origin};
        NoCounters none;
        const ShapeHit nearest = intersect_mesh(mesh, ray, kInfinity, none);
        Real t_max = kInfinity;
        if (k % 3 == 1) t_max = 4 * u(rng);
        if (k % 3 == 2 && nearest.found()) t_max = nearest.t;
        const ShapeHit expected = intersect_mesh(mesh, ray, t_max, none);
        const ShapeHit any = intersect_mesh(mesh, ray, t_max, none, Wanted::any);
        ASSERT_EQ(any.found(), expected.found()) << "ray " << k;
        if (!any.found()) continue;
        ++found;
        farther += any.t > expected.t;
        ASSERT_GT(any.t, 0) << "ray " << k;
        ASSERT_LT(any.t, t_max) << "ray " << k;
        ASSERT_GE(any.t, expected.t) << "ray " << k;
        const glm::uvec3 t = mesh.triangles[any.part];
        const TriangleHit own =
            intersect_triangle(mesh.vertices[t.x], mesh.vertices[t.y], mesh.vertices[t.z], ray);
        ASSERT_EQ(own.t, any.t) << "ray " << k;
        ASSERT_EQ(own.u, any.u) << "ray " << k;
        ASSERT_EQ(own.v, any.v) << "ray " << k;
    }
    EXPECT_GT(found, 10000) << "too few hits to mean much";
    // The any-hit traversal takes each node's children unsorted (it needs no order): 12,446 of
    // the 26,979 first hits are not the nearest (1,237 when they were taken nearest first).
    EXPECT_GT(farther, 500) << "too few first hits beyond the nearest to mean much";
}

// The item buffer's packets (World::intersect_one_packet, the exact resolve's 4×4 blocks that
// name one object): each ray gets intersect_one's answer bit for bit (t, part, u, v), for every
// shape (a mesh through its BVH as a packet, the others ray by ray) and every fill of a packet.
// Rays are aimed at the grid mesh's vertices and edge midpoints (where watertightness and the
// tie rule decide), graze its cells, or are camera blocks and random rays; the transforms are
// random_scene's: thin, sheared, rotated, on a lattice. About 750,000 rays in Release.
TEST(Accel, OneObjectPacketsAgreeExactlyWithSingleRays) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uint64_t rays = 0, mesh_hits = 0;
    const unsigned scenes = testing::kUnderSanitizers ? 40 : 200;
    for (unsigned seed = 0; seed < scenes; ++seed) {
        Scene scene = random_scene(seed, 12);
        scene.camera.eye = {0, 0, 0};
        scene.camera.look_at = {0, 0, -1};
        // The grid, a mesh of 1,062 triangles, placed like the random objects, a tenth its size.
        scene.meshes.push_back(grid_mesh());
        const std::uint32_t grid = static_cast<std::uint32_t>(scene.objects.size());
        SceneObject o = scene.objects.back();
        o.shape = ShapeKind::mesh;
        o.mesh = static_cast<std::uint32_t>(scene.meshes.size() - 1);
        o.transform = o.transform * scale_matrix(DVec3(0.1));
        scene.objects.push_back(o);
        const World world(scene);
        const auto to_world = [&](Vec3 p) {
            return Vec3(DVec3(o.transform * glm::dvec4(DVec3(p), 1.0)) - DVec3(scene.camera.eye));
        };
        for (int packet = 0; packet < 500; ++packet) {
            const std::uint32_t object = packet % 2 ? grid : rng() % grid;
            const std::size_t count = 1 + rng() % kMaxPacket;
            const Vec3 eye(7 * u(rng), 7 * u(rng), 7 * u(rng));
            Ray batch[kMaxPacket];
            constexpr AtGrid kAt[5] = {AtGrid::vertex, AtGrid::edge_midpoint, AtGrid::camera_block,
                                       AtGrid::cell, AtGrid::grazing};
            for (std::size_t r = 0; r < count; ++r) {
                batch[r] = grid_ray(kAt[packet % 5], r, eye, to_world, rng);
                if (packet % 7 == 6) batch[r] = random_ray(rng);
                if (batch[r].direction == Vec3(0.0f)) batch[r].direction = {0, 0, 1};
            }
            Hit hits[kMaxPacket];
            world.intersect_one_packet(object, {batch, count}, hits);
            for (std::size_t r = 0; r < count; ++r, ++rays) {
                const Hit expected = world.intersect_one(object, batch[r]);
                mesh_hits += object == grid && expected.found();
                const auto where = [&] {
                    return "scene " + std::to_string(seed) + " packet " + std::to_string(packet) +
                           " ray " + std::to_string(r);
                };
                ASSERT_EQ(hits[r].object, expected.object) << where();
                ASSERT_EQ(hits[r].t, expected.t) << where();
                ASSERT_EQ(hits[r].primitive, expected.primitive) << where();
                ASSERT_EQ(hits[r].u, expected.u) << where();
                ASSERT_EQ(hits[r].v, expected.v) << where();
            }
        }
    }
    EXPECT_GT(rays, scenes * 500 * 4);
    EXPECT_GT(mesh_hits, rays / 5) << "too few of the grid's hits to mean much";
}

// The list's packets (World::intersect_packet, occluded_packet, opaque_between_packet over the
// list, which takes a mesh met by several rays of a packet as a packet through the mesh's own
// BVH): every ray gets exactly the list's answer ray by ray, t, part and u, v included. Scenes of
// a few random objects (a third of them glass; random_scene's meshes among them) and two grid
// meshes, one of them glass, placed like them; camera blocks and shadow rays aimed at the grids'
// vertices and cells, grazing rays along them and random rays, with skips; every fill of a
// packet. About 640,000 rays in Release, 60% of them hitting a grid first.
TEST(Accel, ListPacketsAgreeExactlyWithTheListRayByRay) {
    std::mt19937 rng(57);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uint64_t rays = 0, mesh_hits = 0, blocked_by_mesh = 0;
    const unsigned scenes = testing::kUnderSanitizers ? 30 : 150;
    for (unsigned seed = 0; seed < scenes; ++seed) {
        Scene scene = random_scene(seed, 6);
        scene.camera.eye = {0, 0, 0};
        scene.camera.look_at = {0, 0, -1};
        make_every_third_glass(scene);
        scene.meshes.push_back(grid_mesh());
        std::uint32_t grids[2];
        for (int g = 0; g < 2; ++g) { // from where the last random objects are, 6 units wide
            grids[g] = static_cast<std::uint32_t>(scene.objects.size());
            SceneObject o = scene.objects[scene.objects.size() - 1 - g];
            o.shape = ShapeKind::mesh;
            o.mesh = static_cast<std::uint32_t>(scene.meshes.size() - 1);
            o.transform = o.transform * scale_matrix(DVec3(0.25));
            if (g == 1) o.material = 1; // make_every_third_glass's glass
            scene.objects.push_back(o);
        }
        const World list(scene, AccelKind::list);
        ASSERT_EQ(list.accelerator().kind(), AccelKind::list);
        for (int packet = 0; packet < 500; ++packet) {
            const SceneObject& grid = scene.objects[grids[packet % 2]];
            const auto to_world = [&](Vec3 p) {
                return Vec3(DVec3(grid.transform * glm::dvec4(DVec3(p), 1.0)) -
                            DVec3(scene.camera.eye));
            };
            const std::size_t count = 1 + rng() % kMaxPacket;
            const Vec3 eye(7 * u(rng), 7 * u(rng), 7 * u(rng));
            Ray batch[kMaxPacket];
            std::uint32_t skips[kMaxPacket];
            constexpr AtGrid kAt[5] = {AtGrid::vertex, AtGrid::camera_block, AtGrid::shadow,
                                       AtGrid::grazing, AtGrid::cell};
            for (std::size_t r = 0; r < count; ++r) {
                batch[r] = grid_ray(kAt[packet % 5], r, eye, to_world, rng);
                if (packet % 7 == 6) batch[r] = random_ray(rng);
                if (batch[r].direction == Vec3(0.0f)) batch[r].direction = {0, 0, 1};
                skips[r] = rng() % 3 == 0 ? grids[rng() % 2] : kNoObject;
            }
            const float t_max = packet % 5 == 2 ? 1.0f : 2 + 10 * (u(rng) + 1);
            ListAnswers answers[kMaxPacket];
            ASSERT_NO_FATAL_FAILURE(expect_packet_agrees(
                list, list, {batch, count}, skips, skips, t_max,
                "scene " + std::to_string(seed) + " packet " + std::to_string(packet), answers));
            for (std::size_t r = 0; r < count; ++r, ++rays) {
                const ListAnswers& a = answers[r];
                const auto on_grid = [&](const Hit& h) {
                    return h.object == grids[0] || h.object == grids[1];
                };
                mesh_hits += on_grid(a.hit);
                blocked_by_mesh += a.occluded && on_grid(a.skipped) && a.skipped.t < t_max;
            }
        }
    }
    EXPECT_GT(rays, scenes * 500 * 4);
    EXPECT_GT(mesh_hits, rays / 5) << "too few of the grids' hits to mean much";
    EXPECT_GT(blocked_by_mesh, rays / 20) << "too few shadow rays the grids block";
}

TEST(Accel, DefaultIsTheListForSmallScenesAndABvhBeyond) {
    const Scene small = random_scene(1, 5);
    EXPECT_EQ(World(small).accelerator().kind(), AccelKind::list);
    const Scene large = random_scene(1, 40);
    EXPECT_EQ(World(large).accelerator().kind(), AccelKind::bvh);
}

} // namespace
} // namespace glint
