// Bad input, in one small header that every reader, writer and command may include: the error
// a reader throws (its message complete, naming the file and the place), the limits on what a
// scene may ask for, and how text from a file is quoted into a message.
#pragma once

#include <cstddef>
#include <cstdint>
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

// Text quoted from a file into a message, as printable ASCII: any other byte as \xNN (a
// terminal must not receive a file's control bytes), and cut after `limit` bytes with "…".
std::string printable(std::string_view text, std::size_t limit = 80);

} // namespace glint
