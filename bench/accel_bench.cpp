// Acceleration structures measured: build time, and rays per second for primary, shadow and
// reflection rays, on random spheres (10² … 10⁶); frame-time scaling with threads; and glint
// against Embree on the same rays in the same run (a 10⁶-triangle terrain and SPD's balls-4:
// single rays, packets, shadow rays; "Peers" below).
//
//   glint bench                                   (everything; a few minutes)
//   glint bench --benchmark_filter='^(Glint|Embree)'   (Google Benchmark's flags pass through)
#include "io/json_loader.h"
#include "io/load_scene.h"
#include "trace/kernel.h"
#include "trace/pixel.h"
#include "trace/render.h"
#include "trace/shading.h"

#include <benchmark/benchmark.h>

#ifdef GLINT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <random>

namespace glint {
namespace {

// n spheres in a cube, radii shrinking as n^(-1/3) so that the filled fraction of the volume,
// and with it what a camera ray meets, stays the same at every n.
Scene spheres(int n) {
    Scene scene = parse_scene(R"({"camera": {"eye": [0, 0, 30], "look_at": [0, 0, 0], "fov_y": 40,
        "width": 256, "height": 256}, "lights": [{"position": [20, 30, 40]}],
        "materials": {"m": {"diffuse": [0.7, 0.7, 0.7], "reflectivity": 0.3}},
        "render": {"max_depth": 1}})",
                              "spheres.json");
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-10, 10);
    const double radius = 1.0 * std::cbrt(1000.0 / n);
    for (int i = 0; i < n; ++i)
        scene.objects.push_back(
            {ShapeKind::sphere, 1,
             translation_matrix({u(rng), u(rng), u(rng)}) * scale_matrix(DVec3(radius)), 0, 0});
    return scene;
}

const World& world(int n, AccelKind kind) {
    static std::map<std::pair<int, AccelKind>, std::unique_ptr<World>> cache;
    auto& w = cache[{n, kind}];
    if (!w) w = std::make_unique<World>(spheres(n), kind);
    return *w;
}

AccelKind kind_of(const benchmark::State& state) {
    return static_cast<AccelKind>(state.range(0));
}

// The structure alone, from the objects' world bounds (World's per-object preparation, about
// 0.7 µs an object, is not part of it).
void Build(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(1)), AccelKind::list);
    std::vector<Bounds> bounds;
    for (const Object& o : w.objects()) bounds.push_back(o.bounds);
    for (auto _ : state) benchmark::DoNotOptimize(Accelerator(kind_of(state), bounds));
    state.SetLabel(std::string(name_of(kind_of(state))));
}

// One thread, camera rays through every pixel.
void PrimaryRays(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(1)), kind_of(state));
    const PinholeCamera& camera = w.camera();
    std::int64_t rays = 0;
    for (auto _ : state) {
        for (int y = 0; y < camera.height(); ++y)
            for (int x = 0; x < camera.width(); ++x)
                benchmark::DoNotOptimize(w.intersect(camera.ray(x, y)));
        rays += camera.width() * camera.height();
    }
    state.SetItemsProcessed(rays);
    state.SetLabel(std::string(name_of(kind_of(state))));
}

// Rays spawned from the primary hits: to the light (any-hit) or mirrored (closest hit).
template <bool kShadow> void SecondaryRays(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(1)), kind_of(state));
    const PinholeCamera& camera = w.camera();
    std::vector<Ray> rays;
    std::vector<std::uint32_t> skips; // the object each ray leaves, if it may ignore it
    for (int y = 0; y < camera.height(); ++y) {
        for (int x = 0; x < camera.width(); ++x) {
            const Ray r = camera.ray(x, y);
            const Hit h = w.intersect(r);
            if (!h.found()) continue;
            const SurfacePoint s = w.surface(r, h);
            const Vec3 from = s.spawn();
            rays.push_back(kShadow ? Ray{from, w.lights()[0].position - from}
                                   : Ray{from, reflect(r.direction, s.normal)});
            skips.push_back(s.skip);
        }
    }
    std::int64_t count = 0;
    for (auto _ : state) {
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if constexpr (kShadow)
                benchmark::DoNotOptimize(w.occluded(rays[i], 1.0f, skips[i]));
            else
                benchmark::DoNotOptimize(w.intersect(rays[i], kInfinity, skips[i]));
        }
        count += static_cast<std::int64_t>(rays.size());
    }
    state.SetItemsProcessed(count);
    state.SetLabel(std::string(name_of(kind_of(state))));
}

void ShadowRays(benchmark::State& state) {
    SecondaryRays<true>(state);
}
void ReflectionRays(benchmark::State& state) {
    SecondaryRays<false>(state);
}

// A whole frame (primary, shadow, one reflection) on all cores, BVH.
void Frame(benchmark::State& state) {
    const World& w = world(static_cast<int>(state.range(0)), AccelKind::bvh);
    for (auto _ : state)
        benchmark::DoNotOptimize(render(w, {static_cast<int>(state.range(1)), nullptr}));
    state.SetItemsProcessed(state.iterations() * w.camera().width() * w.camera().height());
}

void accel_arguments(benchmark::internal::Benchmark* b, int max_list) {
    for (int kind = 0; kind < static_cast<int>(all_values<AccelKind>().size()); ++kind)
        for (int n : {100, 1000, 10000, 100000, 1000000})
            if (kind != 0 || n <= max_list) b->Args({kind, n});
}

BENCHMARK(Build)->Apply([](auto* b) { accel_arguments(b, 1000000); })
    -> Unit(benchmark::kMillisecond);
BENCHMARK(PrimaryRays)
    ->Apply([](auto* b) { accel_arguments(b, 1000); }) -> Unit(benchmark::kMillisecond);
BENCHMARK(ShadowRays)
    ->Apply([](auto* b) { accel_arguments(b, 1000); }) -> Unit(benchmark::kMillisecond);
BENCHMARK(ReflectionRays)
    ->Apply([](auto* b) { accel_arguments(b, 1000); }) -> Unit(benchmark::kMillisecond);
BENCHMARK(Frame)
    ->ArgsProduct({{1000, 10000, 100000, 1000000}, {1, 2}})
    ->ArgNames({"spheres", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// ---------------------------------------------------------------------------------------------
// Peers: the same rays against the same geometry in glint and in Embree 3, in the same run
// (docs/PERFORMANCE.md, "Against Embree"). Two scenes:
//  - Terrain: a fractal-ish height field of 2·707² ≈ 10⁶ triangles, one mesh, seen from above;
//  - Balls: SPD's balls-4 (7,381 spheres and a floor polygon), where the SPD folder is beside
//    the checkout (scenes/spd), as glint's spheres against Embree's sphere geometry.
// Rays, all camera-relative (the World's coordinates; Embree gets the geometry moved likewise):
//  - Closest: single rays from the camera towards random points (incoherent in order);
//  - Packets: a 256×256 camera image in 4×4 blocks (glint's packet size; Embree's
//    rtcIntersect16 takes the same 16 rays, rtcIntersect8 each half block);
//  - Shadow: from the camera image's hits towards a point light, any hit, up to the light; in
//    the image's block order, so that 16 consecutive ones are a tile's shadow packet.
// Each runs on one thread, and on all (Threads:2 here: TBB over chunks of rays, both the same).

struct PeerScene {
    const World* world = nullptr;
    std::vector<Ray> closest;               // single rays
    std::vector<Ray> camera;                // 256×256, 4×4 blocks one after another
    std::vector<Ray> shadow;                // to the light, t in (0, 1)
    std::vector<std::uint32_t> shadow_skip; // the object a shadow ray may skip
    std::vector<glm::vec4> spheres;         // centre, radius (Embree's sphere points)
    std::vector<Vec3> vertices;             // the meshes' triangles, world (camera-relative)
    std::vector<glm::uvec3> triangles;
};

// The World's objects as Embree geometry: spheres (uniform scale and translation) as sphere
// points, meshes and triangles as triangle lists with their vertices placed by M. Other shapes
// are not in the peer scenes.
void gather_geometry(PeerScene& peer) {
    const World& w = *peer.world;
    for (const Object& o : w.objects()) {
        const Transform& m = o.transform;
        if (o.shape == ShapeKind::sphere) {
            const Real radius = m.kind == TransformClass::uniform_scale ? m.scale : 1;
            peer.spheres.push_back(glm::vec4(m.offset, radius));
        } else if (o.params.mesh) {
            const auto base = static_cast<std::uint32_t>(peer.vertices.size());
            for (const Vec3& v : o.params.mesh->vertices)
                peer.vertices.push_back(m.point_to_world(v));
            for (const glm::uvec3& t : o.params.mesh->triangles) peer.triangles.push_back(t + base);
        }
    }
}

// Rays through the scene's camera at 256×256 (camera-relative: from the origin): the image in
// blocks, 2¹⁶ through random points of it in random order, and shadow rays from the image's hits
// towards `light` (camera-relative), in the image's block order.
void make_rays(PeerScene& peer, Camera c, Vec3 light) {
    const World& w = *peer.world;
    c.look_at -= c.eye, c.eye = {0, 0, 0};
    c.width = 256, c.height = 256;
    const PinholeCamera camera(c);
    for_each_in_blocks(0, 0, 256, 256,
                       [&](int x, int y) { peer.camera.push_back(camera.ray(x, y)); });
    std::mt19937 rng(7);
    for (int k = 0; k < 1 << 16; ++k)
        peer.closest.push_back(
            camera.sample_ray(static_cast<int>(rng() % 256), static_cast<int>(rng() % 256),
                              static_cast<int>(rng() % 16), static_cast<int>(rng() % 16), 16));
    for (const Ray& r : peer.camera) { // block by block, as a tile's shadow packets go
        const Hit h = w.intersect(r);
        if (!h.found()) continue;
        const SurfacePoint s = w.surface(r, h);
        peer.shadow.push_back(shadow_ray(s, light));
        peer.shadow_skip.push_back(s.skip);
    }
}

const PeerScene& terrain() {
    static const PeerScene peer = [] {
        static Scene scene;
        static const World world = [] {
            scene.materials.push_back(Material{});
            scene.camera.eye = {0, 15, 18};
            scene.camera.look_at = {0, 0, 0};
            TriangleMesh mesh;
            constexpr int n = 708;
            for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                    const float x = 20.0f * i / (n - 1) - 10, z = 20.0f * j / (n - 1) - 10;
                    const float y = 1.5f * std::sin(0.7f * x) * std::cos(0.5f * z) +
                                    0.4f * std::sin(2.3f * x + 1.7f * z) +
                                    0.1f * std::sin(9.1f * x - 7.3f * z);
                    mesh.vertices.push_back({x, y, z});
                }
            }
            for (std::uint32_t j = 0; j + 1 < n; ++j) {
                for (std::uint32_t i = 0; i + 1 < n; ++i) {
                    const std::uint32_t a = j * n + i;
                    mesh.triangles.push_back({a, a + n, a + 1});
                    mesh.triangles.push_back({a + 1, a + n, a + n + 1});
                }
            }
            scene.meshes.push_back(mesh);
            scene.objects.push_back({ShapeKind::mesh, 0, DMat4(1.0), 0, 0});
            return World(scene);
        }();
        PeerScene out;
        out.world = &world;
        gather_geometry(out);
        make_rays(out, scene.camera, Vec3(5, 20, -5) - Vec3(0, 15, 18));
        return out;
    }();
    return peer;
}

const PeerScene* balls() {
    static const std::unique_ptr<PeerScene> peer = []() -> std::unique_ptr<PeerScene> {
        const std::filesystem::path path = GLINT_SOURCE_DIR "/scenes/spd/balls-4.nff";
        if (!std::filesystem::exists(path)) return nullptr;
        static const Scene scene = load_scene(path);
        static const World world(scene);
        auto out = std::make_unique<PeerScene>();
        out->world = &world;
        gather_geometry(*out);
        make_rays(*out, scene.camera, world.lights()[0].position);
        return out;
    }();
    return peer.get();
}

const PeerScene* peer_of(const benchmark::State& state) {
    return state.range(0) == 0 ? &terrain() : balls();
}

// Runs body(begin, end) over [0, n) (rays or packets) on one thread, or in chunks of 256 on all.
template <class Body> void over_rays(std::size_t n, bool all_threads, const Body& body) {
    if (!all_threads) return body(std::size_t{0}, n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const auto& r) { body(r.begin(), r.end()); });
}

void label(benchmark::State& state, const PeerScene& peer, std::int64_t rays) {
    state.SetItemsProcessed(rays);
    state.SetLabel(std::string(state.range(0) == 0 ? "terrain" : "balls-4") +
                   (state.range(1) ? ", all threads" : ", 1 thread") + ", " +
                   std::to_string(peer.triangles.size()) + " triangles, " +
                   std::to_string(peer.spheres.size()) + " spheres, glint kernel " +
                   std::string(name_of(active_kernel())));
}

// The rays of `rays` one at a time (closest hit).
void glint_single(benchmark::State& state, std::vector<Ray> PeerScene::*rays) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    const std::vector<Ray>& given = peer->*rays;
    std::atomic<std::int64_t> hits = 0;
    for (auto _ : state)
        over_rays(given.size(), state.range(1), [&](std::size_t b, std::size_t e) {
            std::int64_t found = 0;
            for (std::size_t i = b; i < e; ++i) found += peer->world->intersect(given[i]).found();
            hits += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(given.size()));
    state.counters["hits"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}

void GlintClosest(benchmark::State& state) {
    glint_single(state, &PeerScene::closest);
}

// The camera image's rays one at a time, in the same block order: what packets save.
void GlintCameraSingle(benchmark::State& state) {
    glint_single(state, &PeerScene::camera);
}

void GlintPackets(benchmark::State& state) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    std::atomic<std::int64_t> hits = 0;
    const std::size_t packets = peer->camera.size() / kMaxPacket;
    for (auto _ : state)
        over_rays(packets, state.range(1), [&](std::size_t b, std::size_t e) {
            std::int64_t found = 0;
            Hit out[kMaxPacket];
            for (std::size_t p = b; p < e; ++p) {
                peer->world->intersect_packet({&peer->camera[p * kMaxPacket], kMaxPacket}, out);
                for (const Hit& h : out) found += h.found();
            }
            hits += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(peer->camera.size()));
    state.counters["hits"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}

void GlintShadow(benchmark::State& state) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    std::atomic<std::int64_t> blocked = 0;
    for (auto _ : state)
        over_rays(peer->shadow.size(), state.range(1), [&](std::size_t b, std::size_t e) {
            std::int64_t found = 0;
            for (std::size_t i = b; i < e; ++i)
                found += peer->world->occluded(peer->shadow[i], 1.0_r, peer->shadow_skip[i]);
            blocked += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(peer->shadow.size()));
    state.counters["blocked"] =
        static_cast<double>(blocked) / static_cast<double>(state.iterations());
}

void GlintShadowPackets(benchmark::State& state) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    std::atomic<std::int64_t> blocked = 0;
    const std::size_t n = peer->shadow.size();
    for (auto _ : state)
        over_rays((n + kMaxPacket - 1) / kMaxPacket, state.range(1),
                  [&](std::size_t b, std::size_t e) {
                      std::int64_t found = 0;
                      bool out[kMaxPacket];
                      for (std::size_t p = b; p < e; ++p) {
                          const std::size_t first = p * kMaxPacket,
                                            count = std::min<std::size_t>(kMaxPacket, n - first);
                          peer->world->occluded_packet({&peer->shadow[first], count}, 1.0_r,
                                                       &peer->shadow_skip[first], out);
                          for (std::size_t r = 0; r < count; ++r) found += out[r];
                      }
                      blocked += found;
                  });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(n));
    state.counters["blocked"] =
        static_cast<double>(blocked) / static_cast<double>(state.iterations());
}

void peer_arguments(benchmark::internal::Benchmark* b) {
    b->ArgsProduct({{0, 1}, {0, 1}})
        ->ArgNames({"balls", "all"})
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}
BENCHMARK(GlintClosest)->Apply(peer_arguments);
BENCHMARK(GlintCameraSingle)->Apply(peer_arguments);
BENCHMARK(GlintPackets)->Apply(peer_arguments);
BENCHMARK(GlintShadow)->Apply(peer_arguments);
BENCHMARK(GlintShadowPackets)->Apply(peer_arguments);

// ---------------------------------------------------------------------------------------------
// Secondary rays in packets (docs/PERFORMANCE.md, "Round two's last changes, and secondary rays in
// packets"): a frame shaded from its primary hits as render() shades it, tile by tile (one thread),
// with the first `levels` levels of each tile's ray trees cast ahead in packets (TileLighting, as
// `--packet-levels` asks; 0: only the primary hits' shadow rays). Scenes, at 960×540, each in the
// eight-wide BVH, whose traversal alone takes packets: SPD's balls-4, whose reflections all leave
// spheres; the same with its floor a mirror (reflectivity 0.5); SPD's gears-4 (glass gears on a
// mirror floor); the shipped mirrors.json (two facing flat mirrors, max_depth 12; `auto` would take
// the list for its few objects).

struct ShadingScene {
    std::string name;
    std::unique_ptr<World> world;
    std::vector<std::vector<Ray>> rays; // per tile, in TileLighting's order
    std::vector<std::vector<Hit>> hits;
};

const ShadingScene* shading_scene(std::int64_t which) {
    static std::map<std::int64_t, std::unique_ptr<ShadingScene>> scenes;
    auto& out = scenes[which];
    if (out) return out.get();
    const char* const files[] = {"scenes/spd/balls-4.nff",
                                 "scenes/spd/balls-4.nff",
                                 "scenes/spd/gears-4.nff", "scenes/mirrors.json"};
    const char* const names[] = {"balls-4", "balls-4, mirror floor", "gears-4", "mirrors"};
    const std::filesystem::path path = std::string(GLINT_SOURCE_DIR "/") + files[which];
    if (!std::filesystem::exists(path)) return nullptr;
    static std::vector<std::unique_ptr<Scene>> kept; // a World refers to its scene
    Scene& scene = *kept.emplace_back(std::make_unique<Scene>(load_scene(path)));
    scene.camera.width = 960, scene.camera.height = 540;
    if (which == 1)
        for (const SceneObject& o : scene.objects)
            if (o.shape != ShapeKind::sphere) scene.materials[o.material].reflectivity = 0.5f;
    out = std::make_unique<ShadingScene>();
    out->name = names[which];
    out->world = std::make_unique<World>(scene, AccelKind::bvh);
    const PinholeCamera& camera = out->world->camera();
    for (int y0 = 0; y0 < camera.height(); y0 += kTileSize)
        for (int x0 = 0; x0 < camera.width(); x0 += kTileSize) {
            auto& rays = out->rays.emplace_back();
            auto& hits = out->hits.emplace_back();
            for_each_in_blocks(x0, y0, std::min(x0 + kTileSize, camera.width()),
                               std::min(y0 + kTileSize, camera.height()), [&](int x, int y) {
                                   rays.push_back(camera.ray(x, y));
                                   hits.push_back(out->world->intersect(rays.back()));
                               });
        }
    return out.get();
}

void TileShading(benchmark::State& state) {
    const ShadingScene* scene = shading_scene(state.range(0));
    if (!scene) return state.SkipWithError("no scenes/spd in the checkout");
    const int levels = static_cast<int>(state.range(1));
    TileLighting lighting;
    std::int64_t pixels = 0;
    RayCounts rays;
    for (auto _ : state) {
        for (std::size_t t = 0; t < scene->rays.size(); ++t) {
            lighting.prepare(*scene->world, scene->rays[t], scene->hits[t], levels);
            for (std::size_t k = 0; k < scene->rays[t].size(); ++k) {
                const PixelSample sample = shade_pixel(*scene->world, scene->rays[t][k],
                                                       scene->hits[t][k], lighting.at(k));
                benchmark::DoNotOptimize(sample.colour);
                rays += sample.rays;
            }
            pixels += static_cast<std::int64_t>(scene->rays[t].size());
        }
    }
    state.SetItemsProcessed(pixels);
    const auto per_pixel = [&](std::uint64_t n) {
        return static_cast<double>(n) / static_cast<double>(pixels);
    };
    state.counters["reflected"] = per_pixel(rays.reflection);
    state.counters["transmitted"] = per_pixel(rays.transmission);
    state.counters["shadow"] = per_pixel(rays.shadow);
    state.SetLabel(scene->name + ", " + std::to_string(levels) + " levels cast ahead");
}
BENCHMARK(TileShading)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1, 2, 4}})
    ->ArgNames({"scene", "levels"})
    ->Unit(benchmark::kMillisecond);

void MeshBuild(benchmark::State& state) {
    const std::vector<Bounds> triangles = triangle_bounds(terrain().world->mesh(0));
    for (auto _ : state) benchmark::DoNotOptimize(WideBvh(triangles, kTriangleLeaves));
    // The mesh's own tree (leaves aligned to its blocks): how full the collapse makes its nodes.
    const WideBvh& tree = terrain().world->mesh(0).bvh;
    std::size_t lanes = 0;
    for (const WideBvhNode& node : tree.nodes())
        lanes += static_cast<std::size_t>(
            std::count_if(std::begin(node.child), std::end(node.child),
                          [](std::uint32_t child) { return child != kEmptyChild; }));
    char fill[96];
    std::snprintf(fill, sizeof fill, "; the mesh's tree: %zu nodes, %.2f children a node",
                  tree.node_count(),
                  static_cast<double>(lanes) / static_cast<double>(tree.node_count()));
    state.SetLabel(std::to_string(triangles.size()) + " triangles, nodes and item slots " +
                   std::to_string(tree.memory_bytes() >> 20) + " MB" + fill);
}
BENCHMARK(MeshBuild)->Unit(benchmark::kMillisecond);

// A skinned or morphed mesh's structure each frame (DESIGN §14): MeshBuild builds its tree anew;
// this refits the tree to the triangles' new boxes (the cost does not depend on how far they
// moved; the tree's quality does). MeshPrepare is everything a posed mesh is prepared with.
void MeshRefit(benchmark::State& state) {
    const Mesh& mesh = terrain().world->mesh(0);
    const std::vector<Bounds> triangles = triangle_bounds(mesh);
    for (auto _ : state) benchmark::DoNotOptimize(mesh.bvh.refitted(triangles));
    state.SetLabel(std::to_string(triangles.size()) + " triangles");
}
BENCHMARK(MeshRefit)->Unit(benchmark::kMillisecond);

void MeshPrepare(benchmark::State& state) {
    const Mesh& prepared = terrain().world->mesh(0);
    TriangleMesh mesh;
    for (const Vec3& v : prepared.vertices) mesh.vertices.emplace_back(v);
    mesh.triangles = prepared.triangles;
    for (auto _ : state) benchmark::DoNotOptimize(prepare_mesh(mesh));
    state.SetLabel(std::to_string(mesh.triangles.size()) + " triangles");
}
BENCHMARK(MeshPrepare)->Unit(benchmark::kMillisecond);

#ifdef GLINT_HAVE_EMBREE
// The peer scene in Embree: sphere points and one triangle mesh, committed once.
class EmbreeScene {
  public:
    explicit EmbreeScene(const PeerScene& peer)
        : device_(rtcNewDevice(nullptr)), scene_(rtcNewScene(device_)) {
        if (!peer.spheres.empty()) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            auto* points = static_cast<float*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                        4 * sizeof(float), peer.spheres.size()));
            for (std::size_t i = 0; i < peer.spheres.size(); ++i)
                for (int c = 0; c < 4; ++c) points[4 * i + c] = peer.spheres[i][c];
            attach(g);
        }
        if (!peer.triangles.empty()) {
            RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), peer.vertices.size()));
            for (std::size_t i = 0; i < peer.vertices.size(); ++i)
                for (int c = 0; c < 3; ++c) v[3 * i + c] = peer.vertices[i][c];
            auto* t = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), peer.triangles.size()));
            for (std::size_t i = 0; i < peer.triangles.size(); ++i)
                for (int c = 0; c < 3; ++c) t[3 * i + c] = peer.triangles[i][c];
            attach(g);
        }
        rtcCommitScene(scene_);
    }
    ~EmbreeScene() { rtcReleaseScene(scene_), rtcReleaseDevice(device_); }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    RTCScene scene() const { return scene_; }

  private:
    void attach(RTCGeometry g) {
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
    }
    RTCDevice device_;
    RTCScene scene_;
};

const EmbreeScene& embree_of(const benchmark::State& state) {
    static std::map<std::int64_t, std::unique_ptr<EmbreeScene>> scenes;
    auto& s = scenes[state.range(0)];
    if (!s) s = std::make_unique<EmbreeScene>(*peer_of(state));
    return *s;
}

void set_ray(RTCRay& out, const Ray& r, float t_far) {
    out.org_x = r.origin.x, out.org_y = r.origin.y, out.org_z = r.origin.z;
    out.dir_x = r.direction.x, out.dir_y = r.direction.y, out.dir_z = r.direction.z;
    out.tnear = 0, out.tfar = t_far, out.mask = ~0u, out.flags = 0, out.time = 0;
}

// The rays of `rays` one at a time with rtcIntersect1.
void embree_single(benchmark::State& state, std::vector<Ray> PeerScene::*rays) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    const std::vector<Ray>& given = peer->*rays;
    const RTCScene scene = embree_of(state).scene();
    std::atomic<std::int64_t> hits = 0;
    for (auto _ : state)
        over_rays(given.size(), state.range(1), [&](std::size_t b, std::size_t e) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            std::int64_t found = 0;
            for (std::size_t i = b; i < e; ++i) {
                RTCRayHit rh;
                set_ray(rh.ray, given[i], kInfinity);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &context, &rh);
                found += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            hits += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(given.size()));
    state.counters["hits"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}

void EmbreeIntersect1(benchmark::State& state) {
    embree_single(state, &PeerScene::closest);
}

// The camera image's rays one at a time with rtcIntersect1: Embree's own packet gain.
void EmbreeCameraIntersect1(benchmark::State& state) {
    embree_single(state, &PeerScene::camera);
}

// The camera image in packets of `kWidth` rays (16: a 4×4 block; 8: half of one).
template <int kWidth, class RayHitN, class Intersect>
void embree_packets(benchmark::State& state, Intersect intersect) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    const RTCScene scene = embree_of(state).scene();
    std::atomic<std::int64_t> hits = 0;
    const std::size_t packets = peer->camera.size() / kWidth;
    for (auto _ : state)
        over_rays(packets, state.range(1), [&](std::size_t b, std::size_t e) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
            alignas(64) int valid[kWidth];
            std::fill(valid, valid + kWidth, -1);
            std::int64_t found = 0;
            for (std::size_t p = b; p < e; ++p) {
                alignas(64) RayHitN rh;
                for (int k = 0; k < kWidth; ++k) {
                    const Ray& r = peer->camera[p * kWidth + k];
                    rh.ray.org_x[k] = r.origin.x, rh.ray.org_y[k] = r.origin.y,
                    rh.ray.org_z[k] = r.origin.z;
                    rh.ray.dir_x[k] = r.direction.x, rh.ray.dir_y[k] = r.direction.y,
                    rh.ray.dir_z[k] = r.direction.z;
                    rh.ray.tnear[k] = 0, rh.ray.tfar[k] = kInfinity, rh.ray.mask[k] = ~0u;
                    rh.ray.flags[k] = 0, rh.ray.time[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                }
                intersect(valid, scene, &context, &rh);
                for (int k = 0; k < kWidth; ++k)
                    found += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
            }
            hits += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(packets * kWidth));
    state.counters["hits"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
}

void EmbreeIntersect8(benchmark::State& state) {
    embree_packets<8, RTCRayHit8>(state, rtcIntersect8);
}
void EmbreeIntersect16(benchmark::State& state) {
    embree_packets<16, RTCRayHit16>(state, rtcIntersect16);
}

// Embree offsets nothing: the shadow rays start where glint's do (spawned off the surface), and
// a ray leaving a sphere skips it in glint; in Embree it may graze its own sphere, which can only
// add work. The blocked counts show how closely the answers agree.
void EmbreeOccluded1(benchmark::State& state) {
    const PeerScene* peer = peer_of(state);
    if (!peer) return state.SkipWithError("no scenes/spd in the checkout");
    const RTCScene scene = embree_of(state).scene();
    std::atomic<std::int64_t> blocked = 0;
    for (auto _ : state)
        over_rays(peer->shadow.size(), state.range(1), [&](std::size_t b, std::size_t e) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            std::int64_t found = 0;
            for (std::size_t i = b; i < e; ++i) {
                RTCRay ray;
                set_ray(ray, peer->shadow[i], 1.0f);
                ray.tnear = 1e-4f; // its own sphere: Embree has no skip
                rtcOccluded1(scene, &context, &ray);
                found += ray.tfar < 0; // set to −inf when blocked
            }
            blocked += found;
        });
    label(state, *peer, state.iterations() * static_cast<std::int64_t>(peer->shadow.size()));
    state.counters["blocked"] =
        static_cast<double>(blocked) / static_cast<double>(state.iterations());
}

BENCHMARK(EmbreeIntersect1)->Apply(peer_arguments);
BENCHMARK(EmbreeCameraIntersect1)->Apply(peer_arguments);
BENCHMARK(EmbreeIntersect8)->Apply(peer_arguments);
BENCHMARK(EmbreeIntersect16)->Apply(peer_arguments);
BENCHMARK(EmbreeOccluded1)->Apply(peer_arguments);
#endif

} // namespace
} // namespace glint

BENCHMARK_MAIN();
