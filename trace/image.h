// A frame's images: linear float RGB as the tracer makes it, and the 8-bit RGB a PNG holds.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb; // row-major, top row first, 3 bytes a pixel

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3) {}

    std::uint8_t* pixel(int x, int y) {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }
};

// Linear float RGB, row-major, top row first: colour as the tracer computes it, kept in float
// until a writer turns it into a file's format (PNG bytes below, OpenEXR in trace/exr.h).
struct FloatImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb; // 3 floats a pixel

    FloatImage() = default;
    FloatImage(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3) {}

    bool empty() const { return rgb.empty(); }
    float* pixel(std::size_t i) { return &rgb[3 * i]; }
    const float* pixel(std::size_t i) const { return &rgb[3 * i]; }
    template <class V> void set(std::size_t i, const V& c) {
        for (int k = 0; k < 3; ++k) rgb[3 * i + k] = static_cast<float>(c[k]);
    }
};

// The display value of a colour channel: clamped once to [0, 1], then round(255·c).
inline std::uint8_t to_byte(float c) {
    return static_cast<std::uint8_t>(std::lround(255.0f * glm::clamp(c, 0.0f, 1.0f)));
}

// Each channel of `colour` through to_byte: the PNG's rule (DESIGN §2, §11).
Image to_bytes(const FloatImage& colour);

// Writes `bytes` to `path` through a temporary file in the same directory and a rename, so
// that `path` is either untouched or complete. Throws std::runtime_error naming the path.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

void write_png(const std::filesystem::path& path, const Image& image);

// The PNG file write_png writes: 8-bit RGB, deflated in parallel bands.
std::string encode_png(const Image& image);

// Throws std::runtime_error naming the path when it cannot be read as an image.
Image read_png(const std::filesystem::path& path);

} // namespace glint
