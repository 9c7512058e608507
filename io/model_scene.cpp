#include "io/model_scene.h"

#include "io/obj_loader.h"
#include "io/scene_check.h"
#include "trace/shapes/table.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace glint {

std::optional<ModelSphere> model_sphere(const std::vector<SceneObject>& objects,
                                        const std::vector<TriangleMesh>& meshes) {
    // Each object's placed box bounds its points: an object whose box cannot change the answer is
    // skipped, so that 10⁴ instances of a large mesh do not each walk every vertex. The answer is
    // to the bit the one every vertex gives. A mesh's box is its object box's eight corners
    // placed by the same arithmetic as its vertices (`place`): rounding is monotonic in each
    // coordinate, and fixed-order sums of monotonic terms are too (the build turns off
    // contraction into fused multiply-adds), so no placed vertex lies beyond the placed corners;
    // the same holds for `distance`.
    const auto place = [](const DMat4& m, DVec3 p) { return DVec3(m * glm::dvec4(p, 1.0)); };
    struct Placed {
        const SceneObject* object;
        DVec3 lo, hi;
        bool vertices; // a mesh or triangle: its points are its vertices, not its box's corners
    };
    std::vector<Placed> placed;
    UnitBoxes unit_boxes(meshes);
    for (const SceneObject& o : objects) {
        const std::optional<ObjectBox> box = unit_boxes(o);
        if (!box) continue;
        const bool vertices = o.shape == ShapeKind::mesh || o.shape == ShapeKind::triangle;
        Placed p{&o, DVec3(0), DVec3(0), vertices};
        if (vertices) {
            p.lo = DVec3(std::numeric_limits<double>::infinity()), p.hi = -p.lo;
            for (int k = 0; k < 8; ++k) {
                const DVec3 c = place(o.transform, {k & 1 ? box->second.x : box->first.x,
                                                    k & 2 ? box->second.y : box->first.y,
                                                    k & 4 ? box->second.z : box->first.z});
                p.lo = glm::min(p.lo, c), p.hi = glm::max(p.hi, c);
            }
        } else {
            std::tie(p.lo, p.hi) = transformed_box(*box, o.transform);
        }
        placed.push_back(p);
    }
    if (placed.empty()) return std::nullopt;
    const auto each_point = [&](const Placed& p, const auto& visit) {
        if (p.vertices) {
            for (const glm::vec3& v : meshes[p.object->mesh].vertices)
                visit(place(p.object->transform, DVec3(v)));
        } else {
            for (int k = 0; k < 8; ++k)
                visit(DVec3(k & 1 ? p.hi.x : p.lo.x, k & 2 ? p.hi.y : p.lo.y, k & 4 ? p.hi.z : p.lo.z));
        }
    };
    // The box of every point: the objects whose boxes reach farthest along each axis first, then
    // every object whose box is not inside the box found so far.
    DVec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    const auto grow = [&](DVec3 p) { lo = glm::min(lo, p), hi = glm::max(hi, p); };
    for (int axis = 0; axis < 3; ++axis) {
        each_point(*std::min_element(placed.begin(), placed.end(),
                                     [&](const Placed& a, const Placed& b) {
                                         return a.lo[axis] < b.lo[axis];
                                     }),
                   grow);
        each_point(*std::max_element(placed.begin(), placed.end(),
                                     [&](const Placed& a, const Placed& b) {
                                         return a.hi[axis] < b.hi[axis];
                                     }),
                   grow);
    }
    for (const Placed& p : placed)
        if (!(glm::all(glm::greaterThanEqual(p.lo, lo)) && glm::all(glm::lessThanEqual(p.hi, hi))))
            each_point(p, grow);
    if (!(lo.x <= hi.x)) return std::nullopt;
    const DVec3 centre = 0.5 * (lo + hi);
    const auto distance = [&](DVec3 p) { return glm::length(p - centre); };
    // The farthest point: objects by their box's farthest corner, farthest first, until no box
    // reaches beyond the distance found.
    const auto reach = [&](const Placed& p) {
        DVec3 corner;
        for (int a = 0; a < 3; ++a)
            corner[a] = std::abs(p.lo[a] - centre[a]) >= std::abs(p.hi[a] - centre[a]) ? p.lo[a] : p.hi[a];
        return distance(corner);
    };
    std::vector<std::pair<double, const Placed*>> order;
    for (const Placed& p : placed) order.emplace_back(reach(p), &p);
    std::sort(order.begin(), order.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    double radius = 0;
    for (const auto& [far, p] : order) {
        if (far <= radius) break;
        each_point(*p, [&](DVec3 q) { radius = std::max(radius, distance(q)); });
    }
    return ModelSphere{centre, radius};
}

void frame_model(Scene& scene, ModelView view) {
    const std::optional<ModelSphere> sphere = model_sphere(scene);
    if (!sphere) return;
    const DVec3 centre = sphere->centre;
    double radius = sphere->radius;
    // A model that is one point still gets a distance.
    if (!(radius > 0)) radius = std::max(1.0, glm::length(centre)) * 1e-3;
    Camera& c = scene.camera;
    const double half_y = glm::radians(c.fov_y) / 2;
    const double half_x = std::atan(std::tan(half_y) * c.width / c.height);
    // The sphere subtends asin(r/d) from distance d: fitted to kFramingFill of the half angle.
    const double half = std::min(half_x, half_y) * kFramingFill;
    const double distance = radius / std::sin(half);
    c.look_at = centre;
    c.eye = centre + distance * glm::normalize(view == ModelView::front ? kFrontDirection
                                                                        : kFramingDirection);
    c.up = {0.0, 1.0, 0.0};
}

void light_model(Scene& scene, std::optional<DVec3> model_centre) {
    const Camera& c = scene.camera;
    // From the model's centre (a framing camera's look-at point; a file camera's may be anywhere
    // along its view); without a bounded object, from the look-at point.
    if (!model_centre)
        if (const std::optional<ModelSphere> sphere = model_sphere(scene))
            model_centre = sphere->centre;
    const DVec3 centre = model_centre.value_or(c.look_at);
    DVec3 back = c.eye - centre; // from the model towards the eye
    // An eye at the centre: the key light stands off behind the eye, one look-at distance back.
    if (!(glm::length(back) > 0)) back = c.eye - c.look_at;
    DVec3 right = glm::cross(c.up, back);
    if (!(glm::length(right) > 0)) right = glm::cross(DVec3(0, 0, 1), back); // looking along up
    if (!(glm::length(right) > 0)) right = DVec3(1, 0, 0);
    right = glm::normalize(right);
    const DVec3 up = glm::normalize(glm::cross(back, right));
    const double d = glm::length(back);
    // The key light from the upper left, √2 times as far from the centre as the eye; the fill
    // light at the eye.
    scene.lights.push_back({centre + back + d * (0.8 * up - 0.6 * right), glm::vec3(0.7f)});
    scene.lights.push_back({c.eye, glm::vec3(0.2f)});
    scene.ambient = glm::vec3(0.1f);
}

Scene obj_scene(const std::filesystem::path& path, const ModelOptions& options) {
    ObjModel model = load_obj(path);
    Scene scene;
    if (options.size) std::tie(scene.camera.width, scene.camera.height) = *options.size;
    scene.materials.emplace_back();
    scene.material_names.emplace_back("default");
    const std::string stem = path.stem().string();
    for (ObjPart& part : model.parts) {
        SceneObject o;
        o.shape = ShapeKind::mesh;
        if (part.material) {
            add_part_textures(part, scene.textures);
            o.material = static_cast<std::uint32_t>(scene.materials.size());
            scene.materials.push_back(*part.material);
            scene.material_names.push_back(part.material_name);
        }
        o.mesh = static_cast<std::uint32_t>(scene.meshes.size());
        scene.meshes.push_back(std::move(part.mesh));
        scene.objects.push_back(o);
        scene.object_names.push_back(part.material_name.empty() ? stem
                                                                : stem + ":" + part.material_name);
    }
    scene.notes = std::move(model.notes);
    scene.warnings = std::move(model.warnings);
    frame_model(scene, options.view.value_or(ModelView::three_quarter));
    light_model(scene);
    const std::string name = path.string();
    check_scene(scene, [&](const std::string& part) {
        const std::size_t slash = part.find('/');
        const std::string head = part.substr(0, slash);
        if (head == "materials" || head == "meshes" || head == "objects")
            return name + ": " + head.substr(0, head.size() - 1) + " " +
                   part.substr(slash + 1, part.find('/', slash + 1) - slash - 1);
        return name + ": " + head + " (of the framing camera and default lights)";
    });
    return scene;
}

} // namespace glint
