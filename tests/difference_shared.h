// What the difference tests share (difference_test.cpp, difference_gl_test.cpp).
#pragma once

#include "frame/difference.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace glint::testing {

// 200 pixels to explain against a cause map (fewer only where the image has fewer): its first
// 150 differing ones, then pixels that do not differ (every third first), then more that differ.
inline std::vector<std::uint32_t> pixels_to_check(const FrameDifference& d) {
    std::vector<std::uint32_t> differing, same;
    for (std::uint32_t p = 0; p < d.causes.size(); ++p)
        (d.causes[p] != Cause::none ? differing : same).push_back(p);
    std::stable_partition(same.begin(), same.end(), [](std::uint32_t p) { return p % 3 == 0; });
    std::vector<std::uint32_t> pixels(
        differing.begin(), differing.begin() + std::min<std::size_t>(150, differing.size()));
    for (std::size_t i = 0; i < same.size() && pixels.size() < 200; ++i) pixels.push_back(same[i]);
    for (std::size_t i = 150; i < differing.size() && pixels.size() < 200; ++i)
        pixels.push_back(differing[i]);
    return pixels;
}

} // namespace glint::testing
