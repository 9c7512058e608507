// Helpers shared by the tests: scenes from JSON text, and rays in the scene's own coordinates.
#pragma once

#include "io/json_loader.h"
#include "io/load_scene.h"
#include "trace/passes.h"
#include "trace/transform.h"
#include "trace/world.h"

#include <cctype>
#include <string>

namespace glint::testing {

// Under the sanitizers (GLINT_SANITIZE: ASan + UBSan, about ten times slower) the slow property
// and image tests do less of the same work: the sanitizers look for memory errors, which every
// scene, structure and mode those tests run still shows, and the Release run does the full amount.
#ifdef GLINT_SANITIZE
inline constexpr bool kUnderSanitizers = true;
#else
inline constexpr bool kUnderSanitizers = false;
#endif
// What image tests divide their width and height by: a quarter of the pixels under the
// sanitizers, for claims that hold at any size.
inline constexpr int kSanitizerShrink = kUnderSanitizers ? 2 : 1;

// The scenes in scenes/ (README's table), by name: every test over "each shipped scene" uses this.
inline constexpr const char* kShippedScenes[] = {"default",    "mirrors",   "transforms", "shadows",
                                                 "primitives", "instances", "whitted",    "glass"};

// scenes/<name>.json, at the given size (0: the scene's own).
inline Scene shipped(const std::string& name, int width = 0, int height = 0) {
    Scene scene = load_scene(std::string(GLINT_SOURCE_DIR "/scenes/") + name + ".json");
    if (width > 0) scene.camera.width = width, scene.camera.height = height;
    return scene;
}

// A scene whose camera sits at the world origin (so camera-relative coordinates equal the
// scene's own) with the given objects, materials and lights as JSON fragments.
inline Scene scene_at_origin(const std::string& objects, const std::string& materials = "{}",
                             const std::string& lights = "[]", const std::string& extra = "") {
    return parse_scene(R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1]},
                          "materials": )" +
                           materials + R"(, "lights": )" + lights + R"(, "objects": )" + objects +
                           extra + "}",
                       "test.json");
}

// A frame that keeps its pixel centres' primary hits (RenderResult::aovs) besides the image.
inline FrameRequest with_aovs() {
    FrameRequest request;
    request.aovs = true;
    return request;
}

// A gtest parameter name from a sentence: letters and digits kept, everything else '_'.
inline std::string test_name(std::string words) {
    for (char& c : words)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return words;
}

// The same scene seen by the same camera after the world is mapped by p ↦ s·p + d.
inline Scene moved(Scene scene, double s, DVec3 d) {
    const DMat4 m = translation_matrix(d) * scale_matrix(DVec3(s));
    const auto map = [&](DVec3 p) { return DVec3(m * glm::dvec4(p, 1.0)); };
    scene.camera.eye = map(scene.camera.eye);
    scene.camera.look_at = map(scene.camera.look_at);
    for (PointLight& light : scene.lights) light.position = map(light.position);
    for (SceneObject& o : scene.objects) o.transform = m * o.transform;
    return scene;
}

inline Hit cast(const World& world, Vec3 origin, Vec3 direction) {
    return world.intersect({origin, direction});
}

} // namespace glint::testing
