// A frame's images: linear float RGB as the tracer makes it, and the 8-bit RGB a PNG holds.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace glint {

// Storage for a frame's buffers (FrameAllocator): a block of kHugeStorage bytes or more
// is aligned to 2 MB and offered to the kernel for transparent huge pages (Linux's
// madvise(MADV_HUGEPAGE), where it has them), so that the first touch of a 1080p frame's 25 MB
// of pixels takes a dozen page faults instead of six thousand (docs/PERFORMANCE.md, "Tile
// buffers and huge pages"); a smaller one comes from operator new.
inline constexpr std::size_t kHugeStorage = std::size_t{4} << 20;
void* allocate_frame_storage(std::size_t bytes);
void free_frame_storage(void* block, std::size_t bytes);

// std::allocator with allocate_frame_storage's storage: for a frame's per-pixel buffers.
template <class T> struct FrameAllocator : std::allocator<T> {
    template <class U> struct rebind { using other = FrameAllocator<U>; };
    FrameAllocator() = default;
    template <class U> FrameAllocator(const FrameAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) { return static_cast<T*>(allocate_frame_storage(n * sizeof(T))); }
    void deallocate(T* p, std::size_t n) noexcept { free_frame_storage(p, n * sizeof(T)); }
};

// An allocator whose containers leave new elements uninitialised (resize without a value): a
// frame's pixels are all written by its passes, in parallel, so their pages are first touched
// there, not by a serial memset before (which costs more than the writes on a virtual machine).
template <class T> struct UninitialisedAllocator : FrameAllocator<T> {
    template <class U> struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U> UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    template <class U> void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
    template <class U, class... Args> void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// A frame's per-pixel layer (cut-off weights, ids): sized without values, because the frame's
// passes write every pixel, in parallel tiles, which is where its pages are first touched.
template <class T> using FrameLayer = std::vector<T, UninitialisedAllocator<T>>;

// A w×h image of RGB pixels (Image, FloatImage) whose values its UninitialisedAllocator leaves
// unset.
template <class RgbImage> RgbImage uninitialised_rgb(int w, int h) {
    RgbImage image;
    image.width = w, image.height = h;
    image.rgb.resize(static_cast<std::size_t>(w) * h * 3);
    return image;
}

// 8-bit RGB, as a PNG holds it.
struct Image {
    int width = 0;
    int height = 0;
    // Row-major, top row first, 3 bytes a pixel; a frame's on huge pages, like FloatImage's.
    std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>> rgb;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
    // Its pixels left unset, for a caller that writes every one (to_bytes, in parallel).
    static Image uninitialised(int w, int h) { return uninitialised_rgb<Image>(w, h); }

    std::uint8_t* pixel(int x, int y) {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    }
};

// Linear float RGB, row-major, top row first: colour as the tracer computes it, kept in float
// until a writer turns it into a file's format (a PNG of Image's bytes above, io/png.h; OpenEXR,
// io/exr.h).
struct FloatImage {
    int width = 0;
    int height = 0;
    std::vector<float, UninitialisedAllocator<float>> rgb; // 3 floats a pixel

    FloatImage() = default;
    FloatImage(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0.0f) {}
    // Its pixels left unset, for a frame whose passes write every one.
    static FloatImage uninitialised(int w, int h) { return uninitialised_rgb<FloatImage>(w, h); }

    bool empty() const { return rgb.empty(); }
    float* pixel(std::size_t i) { return &rgb[3 * i]; }
    const float* pixel(std::size_t i) const { return &rgb[3 * i]; }
    template <class V> void set(std::size_t i, const V& c) {
        for (int k = 0; k < 3; ++k) rgb[3 * i + k] = static_cast<float>(c[k]);
    }
};

// The display value of a colour channel: clamped once to [0, 1] (NaN to 0), then round(255·c),
// halves away from zero (std::lround's rule). x + 0.5 is exact in double for any float x in
// [0, 255], so truncating it is lround(x), without lround's library call (a 1080p frame makes 6
// million).
inline std::uint8_t to_byte(float c) {
    const float x = 255.0f * (c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f);
    return static_cast<std::uint8_t>(static_cast<int>(static_cast<double>(x) + 0.5));
}

// Each channel of `colour` through to_byte: the PNG's rule (DESIGN §2, §11).
Image to_bytes(const FloatImage& colour);

// `glint render --colour srgb`: each channel clamped to [0, 1] (NaN to 0), through the sRGB
// encoding curve (IEC 61966-2-1: 12.92·c up to 0.0031308, else 1.055·c^(1/2.4) − 0.055), then
// round(255·v) as to_byte does.
std::uint8_t to_srgb_byte(float c);
Image to_srgb_bytes(const FloatImage& colour);

// Row y of to_bytes(colour), or of to_srgb_bytes(colour) with `srgb`: its width·3 bytes at
// `out`. For a writer that encodes a frame row by row (io/png.h's PngRows), with no 8-bit copy
// of the frame.
void row_bytes(const FloatImage& colour, int y, bool srgb, std::uint8_t* out);

// The sRGB decoding curve of a byte, as a linear value in [0, 1] (the inverse of the above).
float srgb_to_linear(std::uint8_t byte);

} // namespace glint
