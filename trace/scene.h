// The scene as loaded and validated (DESIGN.md §7): everything after loading may assume it valid.
#pragma once

#include "trace/math.h"
#include "trace/shapes/mesh.h"
#include "trace/shapes/shape.h"

#include <string>
#include <utility>
#include <vector>

namespace glint {

struct Camera {
    DVec3 eye{0.0, 0.0, 5.0};
    DVec3 look_at{0.0, 0.0, 0.0};
    DVec3 up{0.0, 1.0, 0.0};
    double fov_y = 45.0; // full vertical angle, degrees
    int width = 800;
    int height = 600;
};

struct PointLight {
    DVec3 position;
    Vec3 color{1.0f};
};

struct Material {
    Vec3 ambient{0.8f};
    Vec3 diffuse{0.8f};
    Vec3 specular{0.0f};
    float shininess = 32.0f;
    float reflectivity = 0.0f;
};

struct SceneObject {
    ShapeKind shape = ShapeKind::sphere;
    std::uint32_t material = 0;
    DMat4 transform{1.0};    // object → world, composed from the scene's transform list
    float top_radius = 0.0f; // cones only
    std::uint32_t mesh = 0;  // index into Scene::meshes for triangles and meshes
};

// Object-space bounds of an object's primitive; empty (default) for planes, which have none.
Bounds unit_bounds(const SceneObject& object, const std::vector<Mesh>& meshes);

// The box M·[lo, hi] in double: the eight corners mapped, their smallest and largest coordinates.
std::pair<DVec3, DVec3> transformed_box(const Bounds& local, const DMat4& m);

struct RenderSettings {
    int max_depth = 5;
    float min_reflectivity = 0.01f;
};

struct Scene {
    Camera camera;
    Vec3 background{0.0f};
    Vec3 ambient{0.0f};
    std::vector<PointLight> lights;
    std::vector<Material> materials; // index 0 is the default material
    std::vector<std::string> material_names;
    std::vector<SceneObject> objects;
    std::vector<Mesh> meshes;
    RenderSettings render;
};

} // namespace glint
