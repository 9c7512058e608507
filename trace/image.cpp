#include "trace/image.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <sys/mman.h>
#include <unistd.h>

namespace glint {

void* allocate_frame_storage(std::size_t bytes) {
    if (bytes < kHugeStorage) return ::operator new(bytes);
    constexpr std::size_t kHugePage = std::size_t{2} << 20;
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* block = std::aligned_alloc(kHugePage, rounded);
    if (!block) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(block, rounded, MADV_HUGEPAGE); // advice only: where refused, 4 KB pages serve
#endif
    return block;
}

void free_frame_storage(void* block, std::size_t bytes) {
    if (bytes < kHugeStorage) return ::operator delete(block);
    std::free(block);
}

std::uint8_t to_srgb_byte(float c) {
    const double x = c > 0.0f ? (c < 1.0f ? c : 1.0) : 0.0;
    const double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(static_cast<int>(255.0 * v + 0.5));
}

void row_bytes(const FloatImage& colour, int y, bool srgb, std::uint8_t* out) {
    const std::size_t n = static_cast<std::size_t>(colour.width) * 3;
    const float* in = &colour.rgb[n * static_cast<std::size_t>(y)];
    if (srgb)
        for (std::size_t i = 0; i < n; ++i) out[i] = to_srgb_byte(in[i]);
    else
        for (std::size_t i = 0; i < n; ++i) out[i] = to_byte(in[i]);
}

namespace {

// The rows of `colour` through row_bytes, in parallel.
Image encoded(const FloatImage& colour, bool srgb) {
    Image image = Image::uninitialised(colour.width, colour.height);
    tbb::parallel_for(0, colour.height,
                      [&](int y) { row_bytes(colour, y, srgb, image.pixel(0, y)); });
    return image;
}

} // namespace

Image to_srgb_bytes(const FloatImage& colour) {
    return encoded(colour, true);
}

float srgb_to_linear(std::uint8_t byte) {
    static const auto table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double v = i / 255.0;
            t[i] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table[byte];
}

Image to_bytes(const FloatImage& colour) {
    return encoded(colour, false);
}

} // namespace glint
