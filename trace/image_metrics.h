// How far one image is from another (the pure-ray image is the reference), and pictures of it.
#pragma once

#include "trace/image.h"

#include <span>
#include <vector>

namespace glint {

struct ImageDifference {
    double psnr_db;           // over all 8-bit channels; infinite for identical images
    int max_abs_error;        // in 1/255 steps
    double fraction_over_one; // pixels with any channel off by more than 1/255
    std::uint64_t pixels_over_one;
    double fraction_over_two; // pixels with any channel off by more than 2/255
    // In radiance, over the linear float images (add_radiance_error; 0 until it is called):
    double rmse = 0;               // root mean square of the channels' differences
    double max_radiance_error = 0; // the largest channel difference
};

ImageDifference compare_images(const Image& reference, const Image& test);

// Fills `diff`'s radiance figures from the two float images (trace/image.h) the bytes came from:
// the error that 8-bit bytes hide below 1/255 and clip above 1. Throws std::invalid_argument when
// the sizes differ.
void add_radiance_error(ImageDifference& diff, const FloatImage& reference, const FloatImage& test);

// Heatmap of the largest channel difference per pixel: black where equal, then blue through
// red to white as the error grows (full white at 32/255 and beyond).
Image difference_heatmap(const Image& reference, const Image& test);

// A distinct colour per object id (black for background), for looking at an id buffer.
Image false_colour(const std::vector<std::uint32_t>& ids, int width, int height);

// Fraction of pixels whose primary hits name the same object (per pixel, row-major; both
// missing counts as agreeing).
double id_agreement(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b);

} // namespace glint
