// libFuzzer target: any bytes as an OBJ mesh (io/obj_loader.h), checked as every loader is
// (fuzz/render_check.h). What follows a line "#%mtl" is the material library the OBJ's mtllib
// reads, so that tinyobjloader's MTL parser is fuzzed too. A mesh that loads is placed in a
// scene (each part an object, the camera looking at the mesh's box) and rendered.
#include "fuzz/render_check.h"
#include "io/obj_loader.h"

#include <glm/glm.hpp>

namespace {

glint::Scene obj_scene(const std::string& input, const std::string& name) {
    using namespace glint;
    const std::size_t split = input.find("#%mtl\n");
    const std::string obj = input.substr(0, split);
    const std::string mtl = split == std::string::npos ? "" : input.substr(split + 6);
    const ObjModel model =
        parse_obj(obj, name, [&](const std::string&) { return std::optional<std::string>(mtl); });
    Scene scene;
    scene.materials.push_back(Material{});
    scene.material_names.push_back("default");
    DVec3 lo(kMaxCoordinate), hi(-kMaxCoordinate);
    for (const ObjPart& part : model.parts) {
        SceneObject o;
        o.shape = ShapeKind::mesh;
        o.mesh = static_cast<std::uint32_t>(scene.meshes.size());
        if (part.material) {
            o.material = static_cast<std::uint32_t>(scene.materials.size());
            scene.materials.push_back(*part.material);
            scene.material_names.push_back(part.material_name);
        }
        for (const glm::vec3& v : part.mesh.vertices)
            lo = glm::min(lo, DVec3(v)), hi = glm::max(hi, DVec3(v));
        scene.meshes.push_back(part.mesh);
        scene.objects.push_back(o);
    }
    const DVec3 centre = (lo + hi) * 0.5;
    const double size = std::max(glm::length(hi - lo), 1e-6);
    scene.camera.look_at = centre;
    scene.camera.eye = centre + DVec3(0.3, 0.4, 1.0) * size;
    scene.lights.push_back({scene.camera.eye + DVec3(0, size, 0), glm::vec3(1.0f)});
    return scene;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::check_loader(data, size, "fuzz.obj", obj_scene);
}
