// NFF scenes (Eric Haines' Standard Procedural Databases; docs/SCENES.md, "NFF").
#pragma once

#include "io/error.h"
#include "trace/scene.h"

#include <string>

namespace glint {

// An NFF scene (Standard Procedural Databases; docs/SCENES.md). Errors name `name` and a line.
Scene parse_nff(const std::string& text, const std::string& name);

} // namespace glint
