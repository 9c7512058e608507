// What the difference tests share (difference_test.cpp, difference_gl_test.cpp).
#pragma once

#include "frame/difference.h"

#include <cstdint>
#include <vector>

namespace glint::testing {

// 200 pixels to explain against a cause map: its first 150 differing ones, then every third
// pixel that does not differ until there are 200 (fewer where the image is too small).
inline std::vector<std::uint32_t> pixels_to_check(const FrameDifference& d) {
    std::vector<std::uint32_t> pixels;
    for (std::uint32_t p = 0; p < d.causes.size() && pixels.size() < 150; ++p)
        if (d.causes[p] != Cause::none) pixels.push_back(p);
    for (std::uint32_t p = 0; p < d.causes.size() && pixels.size() < 200; p += 3)
        if (d.causes[p] == Cause::none) pixels.push_back(p);
    return pixels;
}

} // namespace glint::testing
