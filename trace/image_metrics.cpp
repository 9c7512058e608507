#include "trace/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace glint {

ImageDifference compare_images(const Image& reference, const Image& test) {
    double squared = 0;
    int max_error = 0;
    std::uint64_t over = 0, over_two = 0;
    for (std::size_t i = 0; i < reference.rgb.size(); i += 3) {
        int pixel_max = 0;
        for (int c = 0; c < 3; ++c) {
            const int e = std::abs(int(reference.rgb[i + c]) - int(test.rgb[i + c]));
            squared += double(e) * e;
            pixel_max = std::max(pixel_max, e);
        }
        max_error = std::max(max_error, pixel_max);
        over += pixel_max > 1;
        over_two += pixel_max > 2;
    }
    const double pixels = static_cast<double>(reference.rgb.size() / 3);
    const double mse = squared / (3 * pixels);
    return {mse == 0 ? std::numeric_limits<double>::infinity()
                     : 10 * std::log10(255.0 * 255.0 / mse),
            max_error, static_cast<double>(over) / pixels, over,
            static_cast<double>(over_two) / pixels};
}

Image difference_heatmap(const Image& reference, const Image& test) {
    Image out(reference.width, reference.height);
    for (std::size_t i = 0; i < reference.rgb.size(); i += 3) {
        int e = 0;
        for (int c = 0; c < 3; ++c)
            e = std::max(e, std::abs(int(reference.rgb[i + c]) - int(test.rgb[i + c])));
        const float x = std::min(1.0f, static_cast<float>(e) / 32.0f);
        const glm::vec3 colour =
            e == 0     ? glm::vec3(0.0f)
            : x < 0.5f ? glm::mix(glm::vec3(0.1f, 0.2f, 1.0f), glm::vec3(1.0f, 0.1f, 0.1f), x * 2)
                       : glm::mix(glm::vec3(1.0f, 0.1f, 0.1f), glm::vec3(1.0f), (x - 0.5f) * 2);
        for (int c = 0; c < 3; ++c) out.rgb[i + c] = to_byte(colour[c]);
    }
    return out;
}

Image false_colour(const std::vector<std::uint32_t>& ids, int width, int height) {
    Image out(width, height);
    for (std::size_t p = 0; p < ids.size(); ++p) {
        if (ids[p] == 0) continue;
        // Golden-ratio hues: neighbouring ids get well separated colours.
        const float hue = std::fmod(static_cast<float>(ids[p]) * 0.618034f, 1.0f) * 6.0f;
        const glm::vec3 rgb =
            glm::clamp(glm::vec3(std::abs(hue - 3.0f) - 1.0f, 2.0f - std::abs(hue - 2.0f),
                                 2.0f - std::abs(hue - 4.0f)),
                       0.0f, 1.0f);
        for (int c = 0; c < 3; ++c) out.rgb[3 * p + c] = to_byte(0.25f + 0.75f * rgb[c]);
    }
    return out;
}

double id_agreement(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b) {
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
    return a.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(a.size());
}

void add_radiance_error(ImageDifference& diff, const FloatImage& reference,
                        const FloatImage& test) {
    if (reference.width != test.width || reference.height != test.height)
        throw std::invalid_argument("compare: images differ in size");
    double squares = 0, largest = 0;
    for (std::size_t i = 0; i < reference.rgb.size(); ++i) {
        const double d = std::abs(double(test.rgb[i]) - double(reference.rgb[i]));
        squares += d * d;
        largest = std::max(largest, d);
    }
    diff.rmse = reference.rgb.empty() ? 0 : std::sqrt(squares / double(reference.rgb.size()));
    diff.max_radiance_error = largest;
}

} // namespace glint
