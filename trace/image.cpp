#include "trace/image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cerrno>
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

Image to_bytes(const FloatImage& colour) {
    Image image = Image::uninitialised(colour.width, colour.height);
    // In parallel bands of rows: a frame's bytes are made as it is written.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, colour.rgb.size(), 1 << 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              image.rgb[i] = to_byte(colour.rgb[i]);
                      });
    return image;
}

} // namespace glint
