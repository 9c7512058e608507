// PNG files: the 8-bit RGB image a frame's bytes make (trace/image.h's to_bytes), encoded by
// glint (deflated in parallel bands) and written whole (io/write_file.h); read back for tests
// and comparisons.
#pragma once

#include "io/png.h"
#include "trace/image.h"

#include <filesystem>
#include <string>

namespace glint {

void write_png(const std::filesystem::path& path, const Image& image);

// The PNG file write_png writes: 8-bit RGB, deflated in parallel bands.
std::string encode_png(const Image& image);

// Throws std::runtime_error naming the path when it cannot be read as an image.
Image read_png(const std::filesystem::path& path);

} // namespace glint
