// Acceleration structures measured: build time, and rays per second for primary, shadow and
// reflection rays, on random spheres (10² … 10⁶) and on a large triangle mesh, against Embree's
// rtcIntersect1 on the same triangles in the same run; and frame-time scaling with threads.
//
//   glint bench                                   (everything; a few minutes)
//   glint bench --benchmark_filter=Mesh           (Google Benchmark's own flags pass through)
#include "trace/render.h"
#include "trace/scene_loader.h"

#include <benchmark/benchmark.h>

#ifdef GLINT_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

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
// A large triangle mesh: a fractal-ish terrain of 2·707² ≈ 10⁶ triangles, seen from above.

struct Terrain {
    TriangleMesh given; // as a scene holds it
    Mesh mesh;          // as the tracer holds it
    std::vector<Ray> rays;
};

const Terrain& terrain() {
    static const Terrain t = [] {
        Terrain out;
        constexpr int n = 708;
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const float x = 20.0f * i / (n - 1) - 10, z = 20.0f * j / (n - 1) - 10;
                const float y = 1.5f * std::sin(0.7f * x) * std::cos(0.5f * z) +
                                0.4f * std::sin(2.3f * x + 1.7f * z) +
                                0.1f * std::sin(9.1f * x - 7.3f * z);
                out.given.vertices.push_back({x, y, z});
            }
        }
        for (std::uint32_t j = 0; j + 1 < n; ++j) {
            for (std::uint32_t i = 0; i + 1 < n; ++i) {
                const std::uint32_t a = j * n + i;
                out.given.triangles.push_back({a, a + n, a + 1});
                out.given.triangles.push_back({a + 1, a + n, a + n + 1});
            }
        }
        out.mesh = prepare_mesh(out.given);
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(-1, 1);
        for (int k = 0; k < 1 << 16;
             ++k) // from a camera above, towards random points of the terrain
            out.rays.push_back(
                {{0, 15, 18}, glm::normalize(Vec3(9 * u(rng), 0, 9 * u(rng)) - Vec3(0, 15, 18))});
        return out;
    }();
    return t;
}

const World& terrain_world() {
    static const World w = [] {
        Scene scene;
        scene.materials.push_back(Material{});
        scene.camera.eye = {0, 0, 0}; // rays are given in camera-relative coordinates already
        scene.camera.look_at = {0, 0, -1};
        scene.meshes.push_back(terrain().given);
        scene.objects.push_back({ShapeKind::mesh, 0, DMat4(1.0), 0, 0});
        return World(scene);
    }();
    return w;
}

void MeshBuild(benchmark::State& state) {
    const std::vector<Bounds> triangles = triangle_bounds(terrain().mesh);
    for (auto _ : state) benchmark::DoNotOptimize(WideBvh(triangles));
    state.SetLabel(std::to_string(triangles.size()) + " triangles");
}

void MeshRaysGlint(benchmark::State& state) {
    const World& w = terrain_world();
    std::int64_t count = 0, hits = 0;
    for (auto _ : state) {
        for (const Ray& r : terrain().rays) hits += w.intersect(r).found();
        count += static_cast<std::int64_t>(terrain().rays.size());
    }
    state.SetItemsProcessed(count);
    state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(count);
}

BENCHMARK(MeshBuild)->Unit(benchmark::kMillisecond);
BENCHMARK(MeshRaysGlint)->Unit(benchmark::kMillisecond);

#ifdef GLINT_HAVE_EMBREE
// The same rays against the same triangles with Embree's single-ray rtcIntersect1.
void MeshRaysEmbree(benchmark::State& state) {
    const Mesh& mesh = terrain().mesh;
    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices.size()));
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.vertices[i][c];
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (int c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::int64_t count = 0, hits = 0;
    for (auto _ : state) {
        for (const Ray& r : terrain().rays) {
            RTCRayHit rh{};
            rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
            rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y,
            rh.ray.dir_z = r.direction.z;
            rh.ray.tnear = 0, rh.ray.tfar = kInfinity, rh.ray.mask = ~0u, rh.ray.flags = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        count += static_cast<std::int64_t>(terrain().rays.size());
    }
    state.SetItemsProcessed(count);
    state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(count);
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
}
BENCHMARK(MeshRaysEmbree)->Unit(benchmark::kMillisecond);
#endif

} // namespace
} // namespace glint

BENCHMARK_MAIN();
