// libFuzzer target: any bytes as a glTF or GLB model (io/gltf_loader.h), checked as every
// loader is (fuzz/render_check.h): a model that loads is rendered. No file beside it can be read
// (an external buffer or image is refused, as a missing one is). Its seeds are written by
// tests/gltf_seeds.cpp from tests/gltf_builder.h (the fuzz.gltf_seeds test), not downloaded.
#include "fuzz/render_check.h"
#include "io/gltf_loader.h"
#include "io/model_scene.h"
#include "io/scene_check.h"

namespace {

// Read at a time inside most animations, so that the first animation's channels are read and
// checked; then posed at a second time as a sequence does (app/render_command.cpp), the pose held
// to the scene's rules before it is rendered.
glint::Scene gltf_scene(const std::string& input, const std::string& name) {
    glint::ModelOptions options;
    options.time = 0.375;
    glint::Scene scene =
        glint::parse_gltf(input, name,
                          [](const std::string&, std::string& why) {
                              why = "the fuzzer reads no files";
                              return std::optional<std::string>();
                          },
                          options);
    if (scene.animation) {
        scene.animation->pose(scene, 0.5 * scene.animation->duration());
        glint::check_scene(scene, [&](const std::string& path) { return name + ": /" + path; });
    }
    return scene;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::check_loader(data, size, "fuzz.gltf", gltf_scene);
}
