// What a valid scene is, in one place: every loader (JSON, NFF, and the OBJ files a scene names)
// only translates its format into a Scene, then check_scene holds the Scene to every rule here
// (docs/SCENES.md), so a new loader inherits them all. Everything after may assume the scene
// valid (trace/scene.h).
#pragma once

#include "trace/scene.h"

#include <functional>
#include <string>
#include <vector>

namespace glint {

// Where a part of the scene came from in its file, as its loader names places, given the part's
// path in the scene model ("camera/eye/0", "lights/2/position", "materials/4/ior",
// "objects/7/transform", "meshes/1/vertices/12/0", "meshes/1/indices/5", "render/max_depth"):
// the start of an error message, "scenes/x.json: /objects/3/transform" or "balls.nff:12".
using ScenePlaces = std::function<std::string(const std::string& path)>;

// Such a path's parts, split at each '/': "lights/2/position" is {"lights", "2", "position"}.
std::vector<std::string> path_parts(const std::string& path);

// Throws SceneError "PLACE: what is wrong" for the first part of `scene` that breaks a rule.
void check_scene(const Scene& scene, const ScenePlaces& places);

} // namespace glint
