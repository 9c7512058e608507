// load_scene (io/load_scene.h): a scene or a model file, read by its extension. Apart from
// the loaders, so that none of them depends on another through it.
#include "io/load_scene.h"

#include "io/extension.h"
#include "io/gltf_loader.h"
#include "io/json_loader.h"
#include "io/model_scene.h"
#include "io/nff_loader.h"
#include "io/read_text.h"

#include <tuple>

namespace glint {

Scene load_scene(const std::filesystem::path& path, const ModelOptions& options) {
    const std::string name = path.string();
    const std::string extension = extension_of(path);
    if (extension == ".gltf" || extension == ".glb") return load_gltf(path, options);
    if (options.camera)
        throw SceneError(name + ": --camera picks a glTF file's camera; this file has none");
    if (options.animation != 0)
        throw SceneError(name + ": --animation picks a glTF file's animation; this file has none");
    if (extension == ".obj") return obj_scene(path, options);
    // A name without an extension is read as a JSON scene, as it always was.
    if (!extension.empty() && extension != ".json" && extension != ".nff")
        throw SceneError(name + ": unknown scene format '" + printable(extension) +
                         "': glint reads .json, .nff, .obj, .gltf and .glb");
    const std::string text = read_scene_file(path, "scene file");
    Scene scene = extension == ".nff" ? parse_nff(text, name) : parse_scene(text, name);
    if (options.size) std::tie(scene.camera.width, scene.camera.height) = *options.size;
    return scene;
}

} // namespace glint
