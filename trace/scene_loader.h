// Loads and validates JSON scenes (every field and default in docs/SCENES.md).
// Every error names the file and the JSON path (or, for malformed JSON, the line and column).
#pragma once

#include "trace/model_scene.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

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
// Colours (light colours, ambient, material terms): products of three and sums over every light
// stay far inside float's range, so shading never makes inf (nor inf·0 = NaN).
inline constexpr double kMaxColour = 1e6;
// Every light adds a shadow ray to every shaded point; a scene with more is a mistake.
inline constexpr std::size_t kMaxLights = 4096;
// The deepest scene is 6 levels (/objects/i/transform/j/matrix/row); nothing needs more.
inline constexpr int kMaxJsonDepth = 32;

// The whole file, refused beyond kMaxSceneBytes (read no further: /dev/zero ends too). `kind`
// names it in errors ("scene file", "mesh file").
std::string read_scene_file(const std::filesystem::path& path, const std::string& kind);

// Text quoted from a file into a message, as printable ASCII: any other byte as \xNN (a
// terminal must not receive a file's control bytes), and cut after `limit` bytes with "…".
std::string printable(std::string_view text, std::size_t limit = 80);

// A number as scene text writes it ("1", "-2.5e-3", "+4"): finite, the whole token.
bool parse_number(std::string_view token, double& value);

// The file a command is given as its scene, read by its extension (any case): .json, .nff, or a
// model, .obj, .gltf or .glb (trace/model_scene.h); any other is an error naming the five.
// `options.size` replaces the camera's image size before a model is framed; `options.camera`
// picks a glTF camera and is an error for the other formats.
Scene load_scene(const std::filesystem::path& path, const ModelOptions& options = {});

// JSON text nested deeper than `limit` levels is refused at the bracket that goes too deep,
// before it is parsed: a million brackets should cost a message, not a stack.
void check_json_nesting(const std::string& text, const std::string& name, int limit);

// `name` stands for the file in error messages.
Scene parse_scene(const std::string& text, const std::string& name);

// An NFF scene (Standard Procedural Databases; docs/SCENES.md). Errors name `name` and a line.
Scene parse_nff(const std::string& text, const std::string& name);

} // namespace glint
