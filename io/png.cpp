#include "io/png.h"

#include "io/write_file.h"

#include <stb_image.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <cstring>
#include <stdexcept>
#include <vector>

namespace glint {

namespace {

void put_u32(std::string& out, std::uint32_t v) {
    const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                           static_cast<char>(v >> 8), static_cast<char>(v)};
    out.append(bytes, 4);
}

// A PNG chunk written in place: begin_chunk puts its length and type and returns where the type
// starts; the caller appends its `size` bytes of data; end_chunk puts the CRC of type and data.
std::size_t begin_chunk(std::string& out, const char* type, std::size_t size) {
    put_u32(out, static_cast<std::uint32_t>(size));
    const std::size_t start = out.size();
    out.append(type, 4);
    return start;
}
void end_chunk(std::string& out, std::size_t start) {
    const auto* bytes = reinterpret_cast<const Bytef*>(out.data() + start);
    put_u32(out,
            static_cast<std::uint32_t>(crc32(0, bytes, static_cast<uInt>(out.size() - start))));
}
void put_chunk(std::string& out, const char* type, const std::string& data) {
    const std::size_t start = begin_chunk(out, type, data.size());
    out += data;
    end_chunk(out, start);
}

// What one thread reuses from band to band: its pages are touched once, not once a band (the
// first touch of fresh memory, not the deflate, was most of a 1080p write on a virtual machine:
// docs/PERFORMANCE.md, "The PNG's bands in reused buffers").
struct BandScratch {
    std::vector<std::uint8_t> row, above; // a row's bytes, and those of the row above it
    std::vector<Bytef> filtered, out;
};

// Rows [y0, y1), each with its PNG filter byte, deflated as raw blocks that end on a byte
// boundary (Z_SYNC_FLUSH) unless `last`, so that bands concatenate into one stream.
std::string deflate_band(int width, const PngRows& rows, int y0, int y1, bool last, uLong& adler,
                         BandScratch& scratch) {
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    scratch.row.resize(row), scratch.above.resize(row);
    scratch.filtered.resize((row + 1) * static_cast<std::size_t>(y1 - y0));
    if (y0 > 0) rows(y0 - 1, scratch.above.data());
    for (int y = y0; y < y1; ++y) {
        // Filter "Up" (each byte minus the one above; the band's first row too, since PNG
        // filters see the previous row of the image, not of the band): renders vary smoothly
        // down a column, and it costs one subtraction a byte.
        Bytef* out = &scratch.filtered[(row + 1) * static_cast<std::size_t>(y - y0)];
        const std::uint8_t* cur = scratch.row.data();
        rows(y, scratch.row.data());
        out[0] = y == 0 ? 0 : 2;
        if (y == 0) {
            std::copy(cur, cur + row, out + 1);
        } else {
            const std::uint8_t* above = scratch.above.data();
            for (std::size_t i = 0; i < row; ++i)
                out[i + 1] = static_cast<std::uint8_t>(cur[i] - above[i]);
        }
        scratch.row.swap(scratch.above);
    }
    const Bytef* in = scratch.filtered.data();
    adler = adler32(1, in, static_cast<uInt>(scratch.filtered.size()));
    z_stream z{};
    // Level 1 with raw deflate (windowBits −15): the zlib header and checksum are written once,
    // around all the bands.
    if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("zlib: deflateInit2 failed");
    scratch.out.resize(deflateBound(&z, static_cast<uLong>(scratch.filtered.size())) + 16);
    z.next_in = const_cast<Bytef*>(in);
    z.avail_in = static_cast<uInt>(scratch.filtered.size());
    z.next_out = scratch.out.data();
    z.avail_out = static_cast<uInt>(scratch.out.size());
    const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    const std::size_t size = z.total_out;
    deflateEnd(&z);
    if (status != (last ? Z_STREAM_END : Z_OK) || z.avail_in != 0)
        throw std::runtime_error("zlib: deflate failed");
    return std::string(reinterpret_cast<const char*>(scratch.out.data()), size);
}

} // namespace

std::string encode_png(int width, int height, const PngRows& rows) {
    if (width <= 0 || height <= 0) throw std::runtime_error("cannot encode an empty image");
    // Bands of rows deflated in parallel and joined into one zlib stream, as pigz does: a 1080p
    // render is encoded in a fraction of the single-threaded time (docs/PERFORMANCE.md).
    constexpr int kRowsPerBand = 64;
    const int bands = (height + kRowsPerBand - 1) / kRowsPerBand;
    std::vector<std::string> deflated(static_cast<std::size_t>(bands));
    std::vector<uLong> adlers(static_cast<std::size_t>(bands));
    tbb::enumerable_thread_specific<BandScratch> scratch;
    tbb::parallel_for(0, bands, [&](int b) {
        const int y0 = b * kRowsPerBand, y1 = std::min(height, y0 + kRowsPerBand);
        deflated[b] = deflate_band(width, rows, y0, y1, b == bands - 1, adlers[b], scratch.local());
    });
    std::size_t idat_size = 2 + 4; // the zlib header, the bands, the Adler-32 checksum
    for (const std::string& band : deflated) idat_size += band.size();

    // The file in one string, its size known: the compressed data is copied once, into place.
    std::string png = "\x89PNG\r\n\x1a\n";
    png.reserve(png.size() + 25 + (12 + idat_size) + 12); // IHDR, IDAT, IEND
    std::string header;
    put_u32(header, static_cast<std::uint32_t>(width));
    put_u32(header, static_cast<std::uint32_t>(height));
    header += std::string("\x08\x02\x00\x00\x00", 5); // 8-bit RGB, deflate, no interlace
    put_chunk(png, "IHDR", header);

    const std::size_t idat = begin_chunk(png, "IDAT", idat_size);
    png.append("\x78\x01", 2); // zlib header: deflate, 32 KiB window, fastest
    uLong adler = adler32(0, nullptr, 0);
    const std::size_t row_bytes = static_cast<std::size_t>(width) * 3 + 1; // filter byte
    for (int b = 0; b < bands; ++b) {
        png += deflated[b];
        const int band_rows = std::min(height, (b + 1) * kRowsPerBand) - b * kRowsPerBand;
        adler = adler32_combine(adler, adlers[b], static_cast<z_off_t>(row_bytes * band_rows));
    }
    put_u32(png, static_cast<std::uint32_t>(adler));
    end_chunk(png, idat);
    put_chunk(png, "IEND", "");
    return png;
}

std::string encode_png(const Image& image) {
    const std::size_t row = static_cast<std::size_t>(image.width) * 3;
    return encode_png(image.width, image.height,
                      [&](int y, std::uint8_t* out) { std::copy_n(image.pixel(0, y), row, out); });
}

void write_png(const std::filesystem::path& path, int width, int height, const PngRows& rows) {
    write_encoded(path, "PNG", [&] { return encode_png(width, height, rows); });
}

void write_png(const std::filesystem::path& path, const Image& image) {
    write_encoded(path, "PNG", [&] { return encode_png(image); });
}

Image read_png(const std::filesystem::path& path) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
    if (!data)
        throw std::runtime_error("cannot read image " + path.string() + ": " +
                                 stbi_failure_reason());
    Image image(w, h);
    std::memcpy(image.rgb.data(), data, image.rgb.size());
    stbi_image_free(data);
    return image;
}

} // namespace glint
