#include "frame/difference_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace glint {

namespace {

// A 5×9 pixel font for the legends: the characters they write, a glyph as 9 rows of 5 (the
// last two for the descenders of g, j, p, q, y and the comma).
struct Glyph {
    char c;
    const char* rows[9];
};

constexpr Glyph kFont[] = {
    {'a', {".....", ".....", ".###.", "....#", ".####", "#...#", ".####", ".....", "....."}},
    {'b', {"#....", "#....", "####.", "#...#", "#...#", "#...#", "####.", ".....", "....."}},
    {'c', {".....", ".....", ".####", "#....", "#....", "#....", ".####", ".....", "....."}},
    {'d', {"....#", "....#", ".####", "#...#", "#...#", "#...#", ".####", ".....", "....."}},
    {'e', {".....", ".....", ".###.", "#...#", "#####", "#....", ".###.", ".....", "....."}},
    {'f', {"..##.", ".#...", "####.", ".#...", ".#...", ".#...", ".#...", ".....", "....."}},
    {'g', {".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", ".###."}},
    {'h', {"#....", "#....", "####.", "#...#", "#...#", "#...#", "#...#", ".....", "....."}},
    {'i', {"..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###.", ".....", "....."}},
    {'j', {"...#.", ".....", "..##.", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'k', {"#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#.", ".....", "....."}},
    {'l', {".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.", ".....", "....."}},
    {'m', {".....", ".....", "##.#.", "#.#.#", "#.#.#", "#.#.#", "#.#.#", ".....", "....."}},
    {'n', {".....", ".....", "####.", "#...#", "#...#", "#...#", "#...#", ".....", "....."}},
    {'o', {".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###.", ".....", "....."}},
    {'p', {".....", ".....", "####.", "#...#", "#...#", "#...#", "####.", "#....", "#...."}},
    {'q', {".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", "....#"}},
    {'r', {".....", ".....", "#.##.", "##..#", "#....", "#....", "#....", ".....", "....."}},
    {'s', {".....", ".....", ".####", "#....", ".###.", "....#", "####.", ".....", "....."}},
    {'t', {".#...", ".#...", "####.", ".#...", ".#...", ".#..#", "..##.", ".....", "....."}},
    {'u', {".....", ".....", "#...#", "#...#", "#...#", "#..##", ".##.#", ".....", "....."}},
    {'v', {".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#..", ".....", "....."}},
    {'w', {".....", ".....", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#.", ".....", "....."}},
    {'x', {".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", ".....", "....."}},
    {'y', {".....", ".....", "#...#", "#...#", "#...#", "#...#", ".####", "....#", ".###."}},
    {'z', {".....", ".....", "#####", "...#.", "..#..", ".#...", "#####", ".....", "....."}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###.", ".....", "....."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###.", ".....", "....."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####", ".....", "....."}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###.", ".....", "....."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#.", ".....", "....."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###.", ".....", "....."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###.", ".....", "....."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#...", ".....", "....."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###.", ".....", "....."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##..", ".....", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##..", ".....", "....."}},
    {',', {".....", ".....", ".....", ".....", ".....", ".##..", ".##..", "..#..", ".#..."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", ".....", ".....", "....."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", ".....", ".....", "....."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##", ".....", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#.", ".....", "....."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#...", ".....", "....."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", ".....", ".....", "....."}},
    {'|', {"..#..", "..#..", "..#..", "..#..", "..#..", "..#..", "..#..", ".....", "....."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", ".....", ".....", "....."}},
};

const Glyph* glyph(char c) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    for (const Glyph& g : kFont)
        if (g.c == c) return &g;
    return nullptr; // a space, or a character the legends do not write
}

constexpr Rgb kStrip{24, 24, 24};
constexpr Rgb kText{235, 235, 235};
constexpr Rgb kNoError{0, 0, 0}; // the heat map where A and B agree exactly

// A legend's scale: glyphs 2× from 640 pixels wide, so that they stay legible in a large image.
int scale_for(int width) {
    return width >= 640 ? 2 : 1;
}
int cell_width(int s) {
    return 6 * s;
}
int line_height(int s) {
    return 10 * s;
}

void fill(Image& image, int x0, int y0, int w, int h, Rgb colour) {
    for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
        for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x)
            std::copy(colour.begin(), colour.end(), image.pixel(x, y));
}

// Writes `text` with its top left corner at (x, y); clipped to the image.
void draw_text(Image& image, int x, int y, std::string_view text, int s, Rgb colour = kText) {
    for (const char c : text) {
        if (const Glyph* g = glyph(c))
            for (int row = 0; row < 9; ++row)
                for (int col = 0; col < 5; ++col)
                    if (g->rows[row][col] == '#')
                        fill(image, x + col * s, y + row * s, s, s, colour);
        x += cell_width(s);
    }
}

int text_width(std::string_view text, int s) {
    return static_cast<int>(text.size()) * cell_width(s);
}

// The frame's picture with a strip of `lines` legend lines below it, the strip filled.
Image with_strip(int width, int height, int lines) {
    Image image(width, height + legend_height(width, lines));
    fill(image, 0, height, width, image.height - height, kStrip);
    return image;
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

} // namespace

int legend_height(int width, int lines) {
    const int s = scale_for(width);
    return lines * line_height(s) + 4 * s;
}

Rgb cause_colour(Cause cause) {
    switch (cause) {
    case Cause::sampling:
        return {255, 127, 0}; // orange
    case Cause::depth:
        return {228, 26, 28}; // red
    case Cause::cutoff:
        return {190, 80, 220}; // violet
    case Cause::primary:
        return {55, 126, 240}; // blue
    case Cause::secondary:
        return {60, 200, 70}; // green
    case Cause::shadow:
        return {255, 240, 40}; // yellow
    case Cause::precision:
        return {250, 140, 200}; // pink
    case Cause::none:
        break;
    }
    return {96, 96, 96};
}

Rgb heat_colour(double e, double top) {
    // Nine points of a scale whose lightness rises evenly from dark violet through blue, teal and
    // green to yellow (the shape of matplotlib's viridis), joined by straight lines in RGB.
    static constexpr Rgb kScale[] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                     {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                     {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    constexpr int last = static_cast<int>(std::size(kScale)) - 1;
    const double t = std::clamp(top > 0 ? e / top : 0.0, 0.0, 1.0) * last;
    const int i = std::min(static_cast<int>(t), last - 1);
    const double f = t - i;
    Rgb out{};
    for (std::size_t k = 0; k < 3; ++k)
        out[k] = static_cast<std::uint8_t>(
            std::lround(kScale[i][k] + f * (kScale[i + 1][k] - kScale[i][k])));
    return out;
}

double heat_top(const FrameDifference& d) {
    // The 99th percentile of the errors that are not 0: one bright outlier would otherwise leave
    // the rest of the map in the scale's first colour.
    std::vector<float> errors;
    for (const float e : d.error)
        if (e > 0) errors.push_back(e);
    if (errors.empty()) return 1e-6;
    const auto at = errors.begin() + static_cast<std::ptrdiff_t>(0.99 * double(errors.size() - 1));
    std::nth_element(errors.begin(), at, errors.end());
    const double value = std::max(static_cast<double>(*at), 1e-6);
    // Two significant digits, rounded up: 0.2734 → 0.28.
    const double unit = std::pow(10.0, std::floor(std::log10(value)) - 1);
    return std::ceil(value / unit - 1e-9) * unit;
}

Image heat_map(const FrameDifference& d) {
    const int s = scale_for(d.width);
    Image image = with_strip(d.width, d.height, 2);
    const double top = heat_top(d);
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
            const float e = d.error[static_cast<std::size_t>(y) * d.width + x];
            const Rgb c = e > 0 ? heat_colour(e, top) : kNoError;
            std::copy(c.begin(), c.end(), image.pixel(x, y));
        }
    // The scale: a bar from 0 to its top value, then the two values and what is measured.
    const int pad = 2 * s, bar_y = d.height + pad;
    for (int x = pad; x < d.width - pad; ++x)
        fill(image, x, bar_y, 1, 6 * s, heat_colour(x - pad, std::max(1, d.width - 2 * pad - 1)));
    const int text_y = bar_y + line_height(s);
    draw_text(image, pad, text_y, "0", s);
    const std::string top_text = number(top) + (d.largest > top ? "+" : "");
    draw_text(image, d.width - pad - text_width(top_text, s), text_y, top_text, s);
    const std::string what = "radiance error";
    const int middle = (d.width - text_width(what, s)) / 2;
    if (middle > pad + cell_width(s) * 2 &&
        middle + text_width(what, s) < d.width - pad - text_width(top_text, s) - cell_width(s))
        draw_text(image, middle, text_y, what, s);
    return image;
}

Image cause_map(const FrameDifference& d, const Image& a) {
    const int s = scale_for(d.width);
    // The legend's entries, laid out first to know how many lines they take.
    struct Entry {
        Cause cause;
        std::string text;
    };
    std::vector<Entry> entries{{Cause::none, "same"}};
    for (std::size_t c = 1; c < kCauses; ++c)
        if (d.tallies[c].pixels > 0)
            entries.push_back({static_cast<Cause>(c), std::string(name_of(static_cast<Cause>(c))) +
                                                          " " +
                                                          std::to_string(d.tallies[c].pixels)});
    const int pad = 2 * s, swatch = 7 * s;
    std::vector<std::pair<int, int>> at; // each entry's column and line
    int x = pad, line = 0;
    for (const Entry& e : entries) {
        const int w = swatch + cell_width(s) + text_width(e.text, s) + 2 * cell_width(s);
        if (x > pad && x + w > d.width) x = pad, ++line;
        at.emplace_back(x, line);
        x += w;
    }
    Image image = with_strip(d.width, d.height, line + 1);
    for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
            const Cause cause = d.causes[static_cast<std::size_t>(y) * d.width + x];
            std::uint8_t* out = image.pixel(x, y);
            if (cause != Cause::none) {
                const Rgb c = cause_colour(cause);
                std::copy(c.begin(), c.end(), out);
                continue;
            }
            const std::uint8_t* in = a.pixel(x, y);
            // Dimmed grey: A's luma at a third of its brightness, above a floor of 32.
            const double luma = 0.2126 * in[0] + 0.7152 * in[1] + 0.0722 * in[2];
            const auto grey = static_cast<std::uint8_t>(32 + luma / 3);
            out[0] = out[1] = out[2] = grey;
        }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const int ex = at[i].first, ey = d.height + pad + at[i].second * line_height(s);
        fill(image, ex, ey, swatch, swatch, cause_colour(entries[i].cause));
        draw_text(image, ex + swatch + cell_width(s), ey, entries[i].text, s);
    }
    return image;
}

MapThumbnails map_thumbnails(const FrameDifference& d, const Image& a, int width) {
    const int factor = std::max(1, (d.width + width - 1) / std::max(1, width));
    FrameDifference small = d; // the tallies (the legend's counts) and the error's range
    small.width = std::max(1, d.width / factor), small.height = std::max(1, d.height / factor);
    const auto pixels = static_cast<std::size_t>(small.width) * small.height;
    small.causes.assign(pixels, Cause::none);
    small.error.assign(pixels, 0.0f);
    Image small_a(small.width, small.height);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * small.width + x;
            std::array<int, kCauses> votes{};
            for (int v = y * factor; v < std::min(d.height, (y + 1) * factor); ++v)
                for (int u = x * factor; u < std::min(d.width, (x + 1) * factor); ++u) {
                    const std::size_t p = static_cast<std::size_t>(v) * d.width + u;
                    small.error[i] = std::max(small.error[i], d.error[p]);
                    ++votes[static_cast<std::size_t>(d.causes[p])];
                }
            const auto most = std::max_element(votes.begin() + 1, votes.end());
            if (*most > 0) small.causes[i] = static_cast<Cause>(most - votes.begin());
            std::copy_n(a.pixel(x * factor, y * factor), 3, small_a.pixel(x, y));
        }
    return {heat_map(small), cause_map(small, small_a)};
}

} // namespace glint
