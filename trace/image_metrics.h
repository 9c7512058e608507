// How far one image is from another (the pure-ray image is the reference), and pictures of it.
#pragma once

#include "trace/image.h"

#include <vector>

namespace glint {

struct ImageDifference {
    double psnr_db;           // over all 8-bit channels; infinite for identical images
    int max_abs_error;        // in 1/255 steps
    double fraction_over_one; // pixels with any channel off by more than 1/255
    std::uint64_t pixels_over_one;
    double fraction_over_two; // pixels with any channel off by more than 2/255
};

ImageDifference compare_images(const Image& reference, const Image& test);

// Heatmap of the largest channel difference per pixel: black where equal, then blue through
// red to white as the error grows (full white at 32/255 and beyond).
Image difference_heatmap(const Image& reference, const Image& test);

// A distinct colour per object id (black for background), for looking at an id buffer.
Image false_colour(const std::vector<std::uint32_t>& ids, int width, int height);

// Fraction of pixels whose primary hits name the same object (per pixel, row-major; both
// missing counts as agreeing).
double id_agreement(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b);

} // namespace glint
