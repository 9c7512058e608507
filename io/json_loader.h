// JSON scenes, read and validated (every field and default in docs/SCENES.md). Every error
// names the file and the JSON path (or, for malformed JSON, the line and column).
#pragma once

#include "io/error.h"
#include "trace/scene.h"

#include <string>

namespace glint {

// `name` stands for the file in error messages.
Scene parse_scene(const std::string& text, const std::string& name);

} // namespace glint
