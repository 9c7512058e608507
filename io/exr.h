// OpenEXR output (DESIGN §12): the float image as R, G, B, and the AOVs `glint render --aov`
// asks for, each channel 32-bit (FLOAT, or UINT for ids), scan lines, ZIP compression.
#pragma once

#include "io/write_file.h"
#include "trace/image.h"
#include "trace/names.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

// What --aov can add; each has its channels, named as OpenEXR tools expect.
enum class Aov { depth, normal, id, cutoff };

template <> struct EnumNames<Aov> {
    static constexpr auto names = name_table("depth", "normal", "id", "cutoff");
};

// The file's layers, per pixel, row-major, top row first (each may be absent: null).
struct ExrLayers {
    const FloatImage* colour = nullptr;            // R, G, B: linear, unclamped
    const std::vector<float>* depth = nullptr;     // Z: the primary hit's t; +inf for no hit
    const std::vector<float>* normal = nullptr;    // N.X, N.Y, N.Z, 3 a pixel
    const std::vector<std::uint32_t>* id = nullptr; // id: object index + 1, 0 for no hit
    const std::vector<float>* cutoff = nullptr;    // cutoff: trace/cutoff.h's cutoff_radiance
};

// The OpenEXR file for `layers` (colour required). Throws std::runtime_error on a layer of the
// wrong size or when the library fails.
std::string encode_exr(const ExrLayers& layers);

// encode_exr, written through write_file_atomically: `path` is untouched or complete.
void write_exr(const std::filesystem::path& path, const ExrLayers& layers);

// The RGB of the EXR file at `path`, width × height × 3 floats top row first (alpha dropped; a
// luminance-only file as grey). Throws std::runtime_error with OpenEXR's reason.
struct ExrRgb {
    int width = 0, height = 0;
    std::vector<float> rgb;
};
ExrRgb read_exr_rgb(const std::filesystem::path& path);

} // namespace glint
