#include "io/scene_check.h"

#include "io/error.h"
#include "trace/shapes/table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace glint {

namespace {

class Check {
  public:
    explicit Check(const ScenePlaces& places) : places_(places) {}

    [[noreturn]] void fail(const std::string& path, const std::string& message) const {
        throw SceneError(places_(path) + ": " + message);
    }

    static bool within(double v, double lo, double hi) { return v >= lo && v <= hi; }

    void range(const std::string& path, double v, double lo, double hi) const {
        if (within(v, lo, hi)) return;
        std::ostringstream text;
        text << "must be between " << lo << " and " << hi << ", got " << v;
        fail(path, text.str());
    }

    // A position: within ±kMaxCoordinate, so that differences and their squares stay finite.
    static bool bounded(const DVec3& p) {
        return std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
               std::abs(p.z) <= kMaxCoordinate;
    }

    void point(const std::string& path, const DVec3& p) const {
        if (bounded(p)) return;
        for (int i = 0; i < 3; ++i)
            if (!(std::abs(p[i]) <= kMaxCoordinate))
                fail(path + "/" + std::to_string(i), "coordinates must be within ±1e15");
    }

    void colour(const std::string& path, const glm::vec3& c) const {
        for (int i = 0; i < 3; ++i) {
            const std::string at = path + "/" + std::to_string(i);
            if (!(c[i] >= 0)) fail(at, "colour components must not be negative");
            if (!(c[i] <= kMaxColour)) fail(at, "colour components must be at most 1e6");
        }
    }

    void camera(const Camera& c) const {
        point("camera/eye", c.eye);
        point("camera/look_at", c.look_at);
        point("camera/up", c.up);
        if (!(c.fov_y > 0 && c.fov_y < 180))
            fail("camera/fov_y", "must be an angle in degrees strictly between 0 and 180");
        range("camera/width", c.width, 1, kMaxImageSide);
        range("camera/height", c.height, 1, kMaxImageSide);
        const DVec3 forward = c.look_at - c.eye;
        if (glm::length(forward) == 0) fail("camera", "eye and look_at must differ");
        if (glm::length(c.up) == 0) fail("camera/up", "must not be zero");
        if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(c.up))) < 1e-6)
            fail("camera/up", "up is parallel to the viewing direction");
    }

    void material(const std::string& path, const Material& m, const Scene& scene) const {
        colour(path + "/ambient", m.ambient);
        colour(path + "/diffuse", m.diffuse);
        colour(path + "/specular", m.specular);
        range(path + "/shininess", m.shininess, 0, 1e6);
        range(path + "/reflectivity", m.reflectivity, 0, 1);
        range(path + "/transmission", m.transmission, 0, 1);
        if (!usable_ior(m.ior)) fail(path + "/ior", "must be above 0 and at most 100");
        if (m.checker.size != 0) { // 0: no checker
            if (!(m.checker.size > 0 && m.checker.size <= kMaxCoordinate))
                fail(path + "/checker/size", "must be above 0 and at most 1e15");
            colour(path + "/checker/diffuse", m.checker.diffuse);
            colour(path + "/checker/ambient", m.checker.ambient);
        }
        if (m.texture != kNoTexture) {
            if (m.texture >= scene.textures.size()) fail(path + "/texture", "no such texture");
            const TextureImage* image = scene.textures[m.texture].image.get();
            if (!image || image->width <= 0 || image->height <= 0 ||
                image->rgb.size() != std::size_t(image->width) * std::size_t(image->height) * 3)
                fail(path + "/texture", "the texture has no pixels");
        }
    }

    void render(const RenderSettings& r) const {
        range("render/max_depth", r.max_depth, 0, kMaxDepth);
        range("render/min_reflectivity", r.min_reflectivity, 0, 1);
        range("render/samples", r.samples, 1, kMaxSamples);
        range("render/aa_threshold", r.aa_threshold, 0, 1);
    }

    void mesh(const std::string& path, const TriangleMesh& mesh) const {
        if (mesh.vertices.size() > kMaxMeshVertices)
            fail(path + "/vertices", "has " + std::to_string(mesh.vertices.size()) +
                                         " vertices; the limit is " +
                                         std::to_string(kMaxMeshVertices));
        if (mesh.triangles.size() > kMaxMeshTriangles)
            fail(path + "/indices", "has more triangles than the limit of " +
                                        std::to_string(kMaxMeshTriangles));
        // An element's path is spelt out only for a message: a mesh has up to millions of them.
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
            if (const DVec3 p(mesh.vertices[v]); !bounded(p))
                point(path + "/vertices/" + std::to_string(v), p);
        const double last = static_cast<double>(mesh.vertices.size()) - 1;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
            for (int c = 0; c < 3; ++c)
                if (const double index = mesh.triangles[t][c]; !within(index, 0, last))
                    range(path + "/indices/" + std::to_string(3 * t + static_cast<std::size_t>(c)),
                          index, 0, last);
        if (!mesh.normals.empty() && mesh.normals.size() != mesh.vertices.size())
            fail(path + "/normals", "has " + std::to_string(mesh.normals.size()) +
                                        " normals for " + std::to_string(mesh.vertices.size()) +
                                        " vertices");
        for (const auto& [key, uvs] :
             {std::pair{"/uvs", &mesh.uvs}, std::pair{"/uvs1", &mesh.uvs1}}) {
            if (!uvs->empty() && uvs->size() != mesh.vertices.size())
                fail(path + key, "has " + std::to_string(uvs->size()) +
                                     " texture coordinates for " +
                                     std::to_string(mesh.vertices.size()) + " vertices");
            for (std::size_t v = 0; v < uvs->size(); ++v)
                if (!std::isfinite((*uvs)[v].x) || !std::isfinite((*uvs)[v].y))
                    fail(path + key + "/" + std::to_string(v),
                         "texture coordinates must be finite");
        }
    }

    void object(const std::string& path, const SceneObject& o, const Scene& scene,
                UnitBoxes& unit_boxes) const {
        if (o.material >= scene.materials.size()) fail(path + "/material", "no such material");
        const ShapeTraits& traits = shape_traits(o.shape);
        if (traits.keys.vertices) {
            if (o.mesh >= scene.meshes.size()) fail(path, "no such mesh");
            // A single triangle (no indices) must span a plane: its normal is its cross product.
            const TriangleMesh& mesh = scene.meshes[o.mesh];
            if (!traits.keys.indices && mesh.vertices.size() == 3 &&
                glm::length(glm::cross(mesh.vertices[1] - mesh.vertices[0],
                                       mesh.vertices[2] - mesh.vertices[0])) == 0)
                fail("meshes/" + std::to_string(o.mesh) + "/vertices",
                     "the triangle's vertices are collinear");
        }
        if (traits.keys.top_radius) range(path + "/top_radius", o.top_radius, 0, 1e6);
        if (o.open && !traits.keys.open) fail(path + "/open", "this shape cannot be open");
        if (const auto why = why_unusable(o.transform)) fail(path + "/transform", *why);
        // Every point of a placed object, not only its position, must be a position (a mesh
        // vertex of 1e15 scaled by 1e15 is not).
        if (const std::optional<ObjectBox> box = unit_boxes(o)) {
            const auto [lo, hi] = transformed_box(*box, o.transform);
            const DVec3 far = glm::max(glm::abs(lo), glm::abs(hi));
            const double reach = std::max({far.x, far.y, far.z});
            if (!(reach <= kMaxCoordinate)) {
                std::ostringstream message;
                message << "the placed object reaches " << reach
                        << " from the origin; objects must lie within ±1e15";
                fail(path + "/transform", message.str());
            }
        }
    }

  private:
    const ScenePlaces& places_;
};

} // namespace

void check_scene(const Scene& scene, const ScenePlaces& places) {
    const Check check(places);
    // The geometry first: a model's framing camera and default lights are made from its placed
    // meshes, so a bad vertex is blamed on its own place (a glTF accessor and element), not on
    // the camera or light derived from it.
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        check.mesh("meshes/" + std::to_string(m), scene.meshes[m]);
    UnitBoxes unit_boxes(scene.meshes);
    for (std::size_t o = 0; o < scene.objects.size(); ++o)
        check.object("objects/" + std::to_string(o), scene.objects[o], scene, unit_boxes);
    check.camera(scene.camera);
    check.colour("background", scene.background);
    check.colour("ambient", scene.ambient);
    if (scene.lights.size() > kMaxLights)
        check.fail("lights", "has " + std::to_string(scene.lights.size()) +
                                 " lights; the limit is " + std::to_string(kMaxLights));
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const std::string path = "lights/" + std::to_string(i);
        check.point(path + "/position", scene.lights[i].position);
        check.colour(path + "/color", scene.lights[i].color);
    }
    for (std::size_t k = 0; k < scene.materials.size(); ++k)
        check.material("materials/" + std::to_string(k), scene.materials[k], scene);
    check.render(scene.render);
}

std::vector<std::string> path_parts(const std::string& path) {
    std::vector<std::string> parts;
    for (std::size_t at = 0; at <= path.size();) {
        const std::size_t slash = std::min(path.find('/', at), path.size());
        parts.push_back(path.substr(at, slash - at));
        at = slash + 1;
    }
    return parts;
}

} // namespace glint
