// Loads and validates JSON scenes (DESIGN.md §7; every field and default in docs/SCENES.md).
// Every error names the file and the JSON path (or, for malformed JSON, the line and column).
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <stdexcept>
#include <string>

namespace glint {

// Bad input: the message is complete ("scenes/x.json: /objects/3/shape: …").
class SceneError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Limits on what a scene (or the command line overriding it) may ask for.
inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxDepth = 64; // reflections per path
inline constexpr std::uintmax_t kMaxSceneBytes = 64u << 20;
inline constexpr std::size_t kMaxMeshVertices = 1u << 24;
inline constexpr std::size_t kMaxMeshTriangles = 1u << 24;

Scene load_scene(const std::filesystem::path& path);

// `name` stands for the file in error messages.
Scene parse_scene(const std::string& text, const std::string& name);

} // namespace glint
