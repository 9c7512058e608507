// Environments (DESIGN §14): an equirectangular image of linear radiance from a Radiance .hdr or
// an OpenEXR file, or glint's built-in studio, which needs no file.
#pragma once

#include "trace/scene.h"

#include <filesystem>
#include <memory>
#include <string>

namespace glint {

// The names `--environment` and a JSON scene's "environment" take besides a file.
inline constexpr const char* kStudioEnvironment = "studio"; // studio_environment()
inline constexpr const char* kNoEnvironment = "none";       // the background colour

// The environment `spec` names: kStudioEnvironment, or a .hdr or .exr file (a relative path
// taken from `base`). SceneError naming `where` (the flag, or the scene file and its key) and the
// file on any other name, an unreadable file, or a texel that is negative or not finite.
std::shared_ptr<const Environment> load_environment(const std::string& spec,
                                                    const std::filesystem::path& base,
                                                    const std::string& where);

// The built-in studio (docs/SCENES.md, "Environments"): a neutral grey room, brighter overhead
// than underfoot, with two soft panels of light ahead to the left and right and one above, so
// that a metal has something to reflect; made, not read, 256 × 128.
std::shared_ptr<const Environment> studio_environment();

} // namespace glint
