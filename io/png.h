// PNG files: the 8-bit RGB image a frame's bytes make (trace/image.h's to_bytes), encoded by
// glint (deflated in parallel bands) and written whole (io/write_file.h); read back for tests
// and comparisons.
#pragma once

#include "io/png.h"
#include "trace/image.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace glint {

void write_png(const std::filesystem::path& path, const Image& image);

// The PNG file write_png writes: 8-bit RGB, deflated in parallel bands.
std::string encode_png(const Image& image);

// A width×height image given row by row: rows(y, out) puts row y's width·3 bytes at `out`,
// called from several threads at once, each row once or twice (a band's first row also
// serves as the row above the next band). For a writer that has no Image to hand: a frame's
// bytes made from its float image as they are encoded (trace/image.h's row_bytes), with no
// 8-bit copy of the frame in between. The same file as encode_png of the image those rows make.
using PngRows = std::function<void(int y, std::uint8_t* out)>;
void write_png(const std::filesystem::path& path, int width, int height, const PngRows& rows);
std::string encode_png(int width, int height, const PngRows& rows);

// Throws std::runtime_error naming the path when it cannot be read as an image.
Image read_png(const std::filesystem::path& path);

} // namespace glint
