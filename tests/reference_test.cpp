// An independent renderer, written from docs/ARCHITECTURE.md's conventions alone: double precision,
// textbook formulas, no code shared with trace/ beyond the scene model. glint must produce the
// same pixels (±2/255) on random scenes of spheres, planes and boxes under arbitrary affine
// transforms with reflections and shadows, and with glass (refraction, shadows through
// transmissive surfaces) and a checker, away from silhouettes, shadow and checker edges.
#include "io/json_loader.h"
#include "trace/render.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <string>

namespace glint {
namespace {

using glm::dmat3;
using glm::dvec3;
using glm::dvec4;

struct RefHit {
    double t;
    int object;
    int part; // box face, to tell the edges between faces
    dvec3 point, normal;
};

class ReferenceRenderer {
  public:
    explicit ReferenceRenderer(const Scene& scene) : scene_(scene) {
        for (const SceneObject& o : scene.objects) inverses_.push_back(glm::inverse(o.transform));
    }

    // Colour of pixel (i, j), clamped, and a key that changes across every discontinuity along
    // the pixel's path (which object and face is hit, which lights are blocked). With
    // render.samples = N > 1, §11's mean of the N×N clamped samples at i + (a + 0.5)/N,
    // j + (b + 0.5)/N, and the samples' key where they all share one (else a key of its own).
    std::pair<dvec3, std::size_t> pixel(int i, int j) const {
        const Camera& c = scene_.camera;
        const int n = scene_.render.samples;
        const dvec3 forward = glm::normalize(c.look_at - c.eye);
        const dvec3 right = glm::normalize(glm::cross(forward, c.up));
        const dvec3 up = glm::cross(right, forward);
        const double h = std::tan(c.fov_y * M_PI / 360.0), aspect = double(c.width) / c.height;
        dvec3 sum(0);
        std::optional<std::size_t> shared;
        bool mixed = false;
        for (int b = 0; b < n; ++b) {
            for (int a = 0; a < n; ++a) {
                const double x = i + (a + 0.5) / n, y = j + (b + 0.5) / n;
                const dvec3 d =
                    glm::normalize(forward + (2 * x / c.width - 1) * h * aspect * right +
                                   (1 - 2 * y / c.height) * h * up);
                std::size_t key = 0;
                sum += glm::clamp(trace(c.eye, d, 0, 1.0, key), 0.0, 1.0);
                mixed |= shared && *shared != key;
                shared = key;
            }
        }
        const std::size_t unique = ~std::size_t{0} - (std::size_t(j) * c.width + i);
        return {sum / double(n * n), mixed ? unique : *shared};
    }

  private:
    // Where the line o + t·d crosses object `index`'s surface: every root, in increasing t, with
    // the box face it is on (0 for the other shapes).
    std::vector<std::pair<double, int>> roots(int index, dvec3 o, dvec3 d) const {
        const SceneObject& object = scene_.objects[index];
        const glm::dmat4& inv = inverses_[index];
        const dvec3 lo = dvec3(inv * dvec4(o, 1)), ld = dvec3(inv * dvec4(d, 0));
        if (object.shape == ShapeKind::sphere) {
            const double a = glm::dot(ld, ld), b = 2 * glm::dot(lo, ld), c = glm::dot(lo, lo) - 1;
            const double disc = b * b - 4 * a * c;
            if (disc < 0) return {};
            return {{(-b - std::sqrt(disc)) / (2 * a), 0}, {(-b + std::sqrt(disc)) / (2 * a), 0}};
        }
        if (object.shape == ShapeKind::plane) return {{-lo.y / ld.y, 0}};
        double t_in = -1e300, t_out = 1e300; // the box
        int face_in = 0, face_out = 0;
        for (int k = 0; k < 3; ++k) {
            double ta = (-1 - lo[k]) / ld[k], tb = (1 - lo[k]) / ld[k];
            int fa = 2 * k, fb = 2 * k + 1;
            if (ta > tb) std::swap(ta, tb), std::swap(fa, fb);
            if (ta > t_in) t_in = ta, face_in = fa;
            if (tb < t_out) t_out = tb, face_out = fb;
        }
        if (t_in > t_out) return {};
        return {{t_in, face_in}, {t_out, face_out}};
    }

    std::optional<RefHit> hit_object(int index, dvec3 o, dvec3 d) const {
        const auto all = roots(index, o, d);
        const auto first = std::find_if(all.begin(), all.end(),
                                        [](const auto& root) { return root.first > kEpsilon; });
        if (first == all.end()) return std::nullopt;
        const auto [t, part] = *first;
        const glm::dmat4& inv = inverses_[index];
        dvec3 n_local(0, 1, 0); // the plane's
        if (scene_.objects[index].shape == ShapeKind::sphere) {
            n_local = dvec3(inv * dvec4(o, 1)) + t * dvec3(inv * dvec4(d, 0));
        } else if (scene_.objects[index].shape == ShapeKind::box) {
            n_local = dvec3(0);
            n_local[part / 2] = part % 2 ? 1 : -1;
        }
        // Normals by the inverse transpose (Ray Tracing III).
        const dvec3 n = glm::normalize(glm::transpose(dmat3(inv)) * n_local);
        return RefHit{t, index, part, o + t * d, n};
    }

    // How many times the segment o + t·d, t in (kEpsilon, 1), crosses object `index`'s surface.
    int crossings(int index, dvec3 o, dvec3 d) const {
        int count = 0;
        for (const auto& [t, part] : roots(index, o, d)) count += t > kEpsilon && t < 1;
        return count;
    }

    std::optional<RefHit> closest(dvec3 o, dvec3 d) const {
        std::optional<RefHit> best;
        for (int k = 0; k < static_cast<int>(scene_.objects.size()); ++k) {
            const auto h = hit_object(k, o, d);
            if (h && (!best || h->t < best->t)) best = h;
        }
        return best;
    }

    dvec3 trace(dvec3 o, dvec3 d, int depth, double weight, std::size_t& key) const {
        const auto hit = closest(o, d);
        key = key * 1000003 + (hit ? hit->object * 8 + hit->part + 1 : 0);
        if (!hit) return dvec3(scene_.background);
        const SceneObject& object = scene_.objects[hit->object];
        const Material& m = scene_.materials[object.material];
        const bool entering = glm::dot(hit->normal, d) < 0;
        dvec3 n = hit->normal;
        if (!entering) n = -n;
        const dvec3 p = hit->point, v = -glm::normalize(d);
        const double eps = 1e-9 * (1 + glm::length(p)); // double leaves room for a plain epsilon
        const dvec3 start = p + eps * n, behind = p - eps * n;
        // The checker at the object-space point, in the floor sense.
        dvec3 ambient(m.ambient), diffuse(m.diffuse);
        if (m.checker.size > 0) {
            const dvec3 q = dvec3(inverses_[hit->object] * dvec4(p, 1));
            const double s = m.checker.size;
            double k = std::floor(q.x / s) + std::floor(q.z / s);
            if (object.shape != ShapeKind::plane) k += std::floor(q.y / s);
            const bool odd = std::fmod(k, 2.0) != 0;
            key = key * 7 + odd;
            if (odd) ambient = dvec3(m.checker.ambient), diffuse = dvec3(m.checker.diffuse);
        }
        dvec3 colour = ambient * dvec3(scene_.ambient);
        for (const PointLight& light : scene_.lights) {
            const dvec3 l = glm::normalize(light.position - p);
            if (glm::dot(n, l) <= 0) continue;
            // The product of the transmissions of every crossing on the way to the light.
            double through = 1;
            int crossed = 0;
            for (int k = 0; k < static_cast<int>(scene_.objects.size()); ++k) {
                const int c = crossings(k, start, light.position - start);
                crossed += c;
                through *=
                    std::pow(double(scene_.materials[scene_.objects[k].material].transmission), c);
            }
            key = key * 31 + crossed;
            if (through == 0) continue;
            const dvec3 r = 2.0 * n * glm::dot(n, l) - l;
            colour +=
                through * dvec3(light.color) *
                (diffuse * glm::dot(n, l) +
                 dvec3(m.specular) * std::pow(std::max(0.0, glm::dot(r, v)), double(m.shininess)));
        }
        const auto follow = [&](double factor, dvec3 from, dvec3 direction) {
            const double w = weight * factor;
            if (factor > 0 && depth < scene_.render.max_depth &&
                w >= scene_.render.min_reflectivity)
                colour += factor * trace(from, direction, depth + 1, w, key);
        };
        follow(m.reflectivity, start, d - 2.0 * n * glm::dot(n, d));
        if (m.transmission > 0) {
            // Snell's law in Heckbert's form, from the unit direction.
            const dvec3 u = glm::normalize(d);
            const double eta = entering ? 1 / double(m.ior) : double(m.ior);
            const double c = -glm::dot(n, u), k = 1 - eta * eta * (1 - c * c);
            key = key * 3 + (k < 0);
            if (k < 0)
                follow(m.transmission, start, u - 2.0 * n * glm::dot(n, u));
            else
                follow(m.transmission, behind, eta * u + (eta * c - std::sqrt(k)) * n);
        }
        return colour;
    }

    static constexpr double kEpsilon = 1e-9;
    const Scene& scene_;
    std::vector<glm::dmat4> inverses_;
};

// A random scene: a floor, and spheres and boxes under random affine maps (shear included).
Scene random_scene(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1), pos(0, 1);
    Scene scene = parse_scene(R"({"camera": {"width": 96, "height": 72, "fov_y": 50},
        "ambient": [0.15, 0.15, 0.15], "background": [0.1, 0.2, 0.3],
        "render": {"max_depth": 4, "min_reflectivity": 0.01}})",
                              "random.json");
    const double angle = u(rng) * M_PI;
    scene.camera.eye = {7 * std::cos(angle), 3 + 2 * pos(rng), 7 * std::sin(angle)};
    scene.camera.look_at = {0, 0.5, 0};
    scene.lights = {{{5, 8, 4}, {0.7f, 0.7f, 0.6f}}, {{-6, 5, -3}, {0.3f, 0.35f, 0.45f}}};
    const float reflectivities[] = {0.0f, 0.3f, 0.8f};
    for (int k = 0; k < 4; ++k) {
        Material m;
        m.diffuse = Vec3(0.2 + 0.7 * pos(rng), 0.2 + 0.7 * pos(rng), 0.2 + 0.7 * pos(rng));
        m.ambient = m.diffuse;
        m.specular = Vec3(0.5f * static_cast<float>(pos(rng)));
        m.shininess = static_cast<float>(5 + 60 * pos(rng));
        m.reflectivity = reflectivities[k % 3];
        scene.materials.push_back(m);
    }
    scene.objects.push_back({ShapeKind::plane, 1, DMat4(1.0), 0, 0});
    for (int k = 0; k < 7; ++k) {
        DMat4 m(1.0);
        do {
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) m[c][r] = (c == r ? 0.7 : 0.0) + 0.35 * u(rng);
        } while (why_unusable(m) || std::abs(glm::determinant(dmat3(m))) < 0.1);
        m[3] = dvec4(3 * u(rng), 1 + 0.5 * pos(rng), 3 * u(rng), 1);
        scene.objects.push_back({k % 2 ? ShapeKind::box : ShapeKind::sphere,
                                 static_cast<std::uint32_t>(1 + k % 4), m, 0, 0});
    }
    return scene;
}

// glint's image against the reference on every pixel whose 3×3 neighbourhood follows one path
// (no edge through it), within `tolerance`/255; returns how many pixels were compared and how
// many of those reflected.
struct ReferenceMatch {
    int compared = 0, reflected = 0;
    double within_two = 0; // of every pixel, edges included: the share within 2/255
};

ReferenceMatch expect_matches_reference(const Scene& scene, const std::string& label,
                                        int tolerance = 2) {
    const Image image = render(World(scene)).bytes();
    const ReferenceRenderer reference(scene);
    const int w = scene.camera.width, h = scene.camera.height;
    std::vector<std::size_t> keys(static_cast<std::size_t>(w) * h);
    std::vector<dvec3> colours(keys.size());
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            std::tie(colours[j * w + i], keys[j * w + i]) = reference.pixel(i, j);
    int compared = 0, reflected = 0, within_two = 0;
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            bool within = true;
            for (int k = 0; k < 3; ++k)
                within &=
                    std::abs(image.pixel(i, j)[k] - std::lround(255 * colours[j * w + i][k])) <= 2;
            within_two += within;
        }
    }
    for (int j = 1; j + 1 < h; ++j) {
        for (int i = 1; i + 1 < w; ++i) {
            bool interior = true; // same path key as all 8 neighbours: no edge through this pixel
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                    interior &= keys[(j + dj) * w + i + di] == keys[j * w + i];
            if (!interior) continue;
            ++compared;
            const dvec3 c = colours[j * w + i];
            for (int k = 0; k < 3; ++k) {
                const long expected = std::lround(255 * c[k]);
                EXPECT_NEAR(image.pixel(i, j)[k], expected, tolerance)
                    << label << " pixel " << i << "," << j;
            }
            reflected += keys[j * w + i] > 1000003u * 64u; // the path went beyond its first hit
        }
    }
    return {compared, reflected, static_cast<double>(within_two) / (w * h)};
}

class ReferenceTest : public ::testing::TestWithParam<unsigned> {};

TEST_P(ReferenceTest, GlintMatchesAnIndependentRendererAwayFromEdges) {
    const Scene scene = random_scene(GetParam());
    const auto [compared, reflected, within_two] =
        expect_matches_reference(scene, "seed " + std::to_string(GetParam()));
    // Enough pixels compared for the test to mean something.
    EXPECT_GT(compared, scene.camera.width * scene.camera.height / 2) << "seed " << GetParam();
    EXPECT_GT(reflected, 0);
}

TEST(Reference, NoShadowOrReflectionAcneWhereMillimetreAndKilometreObjectsMeet) {
    // Millimetre spheres and a box on a kilometre-wide reflective floor, a kilometre mirror
    // sphere behind, one light near and one far. Acne (a surface shadowing or reflecting itself
    // at the spawn point) or a spawn offset larger than a small neighbour costs ≥ 20/255 here:
    // the floor's offset was 2.2e-3, more than the spheres' radius, and lost their reflections
    // (204 pixels off by up to 36/255) until rays leaving convex and planar surfaces skipped
    // them instead. What remains is float's placement of the floor's points, ±γ·(|L||p| + |t|)
    // ≈ 5e-4 for a box of 1000 translated by 1000: half a sphere's radius and a tenth of the
    // near light's distance, so shading there may differ by a few percent (measured: 13 of
    // 6,912 pixels, at most 6/255, all under the small spheres). Hence 8/255, not 2.
    const Scene scene = parse_scene(R"({
        "camera": {"eye": [0, 0.003, 0.008], "look_at": [0, 0.001, 0], "fov_y": 50, "width": 96, "height": 72},
        "ambient": [0.1, 0.1, 0.1], "background": [0.2, 0.3, 0.4],
        "lights": [{"position": [1000, 2000, 1000], "color": [0.6, 0.6, 0.6]},
                   {"position": [0.005, 0.005, 0.005], "color": [0.5, 0.4, 0.3]}],
        "materials": {"floor": {"diffuse": [0.6, 0.6, 0.5], "specular": [0.3, 0.3, 0.3], "shininess": 20, "reflectivity": 0.3},
                      "small": {"diffuse": [0.8, 0.2, 0.2], "specular": [0.5, 0.5, 0.5], "shininess": 50, "reflectivity": 0.5},
                      "mirror": {"diffuse": [0.1, 0.1, 0.1], "reflectivity": 0.8}},
        "render": {"max_depth": 4, "min_reflectivity": 0.01},
        "objects": [
          {"shape": "box", "material": "floor", "transform": [{"scale": 1000}, {"translate": [0, -1000, 0]}]},
          {"shape": "sphere", "material": "small", "transform": [{"scale": 0.001}, {"translate": [0, 0.001, 0]}]},
          {"shape": "sphere", "material": "small", "transform": [{"scale": 0.001}, {"translate": [0.0025, 0.001, -0.001]}]},
          {"shape": "box", "material": "small", "transform": [{"scale": 0.0005}, {"rotate": {"axis": [0, 1, 0], "degrees": 30}}, {"translate": [-0.002, 0.0005, 0.001]}]},
          {"shape": "sphere", "material": "mirror", "transform": [{"scale": 1000}, {"translate": [0, 1000, -3000]}]}]})",
                                    "mixed.json");
    const auto [compared, reflected, within_two] =
        expect_matches_reference(scene, "mixed scales", 8);
    EXPECT_GT(compared, scene.camera.width * scene.camera.height / 2);
    EXPECT_GT(reflected, compared / 2) << "the floor and the small objects all reflect";
}

// The same random scenes with §11's additions: the floor checkered, and one material in four
// glass (transmission, a little reflection), so that refraction, shadows through glass and
// total internal reflection all occur.
class GlassReferenceTest : public ::testing::TestWithParam<unsigned> {};

TEST_P(GlassReferenceTest, GlintMatchesAnIndependentRendererOnGlassScenes) {
    Scene scene = random_scene(GetParam());
    scene.materials[1].checker = {1.5f, glm::vec3(0.9f, 0.85f, 0.2f), glm::vec3(0.9f, 0.85f, 0.2f)};
    Material& glass = scene.materials[4];
    glass.transmission = 0.75f;
    glass.ior = 1.45f;
    glass.reflectivity = 0.1f;
    glass.diffuse = glm::vec3(0.05f);
    const auto [compared, reflected, within_two] =
        expect_matches_reference(scene, "glass seed " + std::to_string(GetParam()));
    // Checker cells and refracted edges leave fewer pixels off every edge than the opaque scenes
    // do: a fifth of the image (1,382 pixels) must still be compared (measured: 1,612 to 2,142).
    EXPECT_GT(compared, scene.camera.width * scene.camera.height / 5) << "seed " << GetParam();
    EXPECT_GT(reflected, 0);
}

// §11's antialiasing: the mean of each pixel's N×N clamped samples, on the opaque and the glass
// scenes. Pixels with an edge among their own or their neighbours' samples are left out as
// above; the rest must match as closely as single samples do.
class SampledReferenceTest : public ::testing::TestWithParam<unsigned> {};

TEST_P(SampledReferenceTest, GlintsSampleGridMatchesAnIndependentRenderer) {
    const unsigned seed = GetParam();
    Scene scene = random_scene(seed);
    scene.render.samples = 2 + static_cast<int>(seed % 2); // 2×2 and 3×3
    if (seed > 2) {
        scene.materials[1].checker = {1.5f, glm::vec3(0.9f, 0.85f, 0.2f),
                                      glm::vec3(0.9f, 0.85f, 0.2f)};
        scene.materials[4].transmission = 0.75f;
    }
    const std::string label = "seed " + std::to_string(seed) + ", " +
                              std::to_string(scene.render.samples) + "x" +
                              std::to_string(scene.render.samples);
    const auto [compared, reflected, within_two] = expect_matches_reference(scene, label);
    // A 3×3 grid sees an edge a third of a pixel further than one sample does, so fewer pixels
    // are left to compare: measured 1,183 (seed 4, glass) to 4,447 of 6,912.
    EXPECT_GT(compared, scene.camera.width * scene.camera.height / 8) << label;
    // Issue 24's goal, on every pixel, edges included: at a silhouette one sample in N² may
    // flip between two objects (float against double), which moves the mean by 1/N² of the
    // step there. Measured: 99.93% to 100% of the pixels.
    EXPECT_GE(within_two, 0.995) << label;
    RecordProperty("within_2_255", std::to_string(within_two));
    EXPECT_GT(reflected, 0) << label;
}

INSTANTIATE_TEST_SUITE_P(RandomScenes, SampledReferenceTest, ::testing::Range(1u, 5u),
                         [](const auto& info) { return "seed_" + std::to_string(info.param); });

INSTANTIATE_TEST_SUITE_P(RandomScenes, GlassReferenceTest, ::testing::Range(1u, 5u),
                         [](const auto& info) { return "seed_" + std::to_string(info.param); });

INSTANTIATE_TEST_SUITE_P(RandomScenes, ReferenceTest, ::testing::Range(1u, 7u),
                         [](const auto& info) { return "seed_" + std::to_string(info.param); });

} // namespace
} // namespace glint
