// Helpers shared by the tests: scenes from JSON text, and rays in the scene's own coordinates.
#pragma once

#include "trace/scene_loader.h"
#include "trace/world.h"

#include <cctype>
#include <string>

namespace glint::testing {

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

// A gtest parameter name from a sentence: letters and digits kept, everything else '_'.
inline std::string test_name(std::string words) {
    for (char& c : words)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return words;
}

inline Hit cast(const World& world, Vec3 origin, Vec3 direction) {
    return world.intersect({origin, direction});
}

} // namespace glint::testing
