// An 8-bit RGBA PNG made in memory, for tests and seeds that need a texture with alpha (glint's
// own writer, io/png.h, writes the RGB frames it renders). Unfiltered rows, one zlib stream.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint::testing {

inline std::string rgba_png(int width, int height, const std::vector<std::uint8_t>& rgba) {
    const auto u32 = [](std::string& out, std::uint32_t v) {
        for (int s = 24; s >= 0; s -= 8) out += static_cast<char>((v >> s) & 0xff);
    };
    const auto chunk = [&](std::string& out, const char* type, const std::string& data) {
        u32(out, static_cast<std::uint32_t>(data.size()));
        const std::string body = std::string(type, 4) + data;
        out += body;
        u32(out, static_cast<std::uint32_t>(crc32(
                     0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
    };
    std::string rows;
    for (int y = 0; y < height; ++y) {
        rows += '\0'; // filter: none
        rows.append(reinterpret_cast<const char*>(&rgba[static_cast<std::size_t>(y) * width * 4]),
                    static_cast<std::size_t>(width) * 4);
    }
    uLongf size = compressBound(static_cast<uLong>(rows.size()));
    std::string deflated(size, '\0');
    if (compress(reinterpret_cast<Bytef*>(deflated.data()), &size,
                 reinterpret_cast<const Bytef*>(rows.data()), static_cast<uLong>(rows.size())) != Z_OK)
        throw std::runtime_error("zlib: compress failed");
    deflated.resize(size);
    std::string header;
    u32(header, static_cast<std::uint32_t>(width));
    u32(header, static_cast<std::uint32_t>(height));
    header += std::string("\x08\x06\x00\x00\x00", 5); // 8 bits, RGBA, deflate, no filter, no interlace
    std::string out = "\x89PNG\r\n\x1a\n";
    chunk(out, "IHDR", header);
    chunk(out, "IDAT", deflated);
    chunk(out, "IEND", "");
    return out;
}

} // namespace glint::testing
