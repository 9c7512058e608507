// The EXR encoder and decoder as a plug-in (glint_exr, io/CMakeLists.txt): OpenEXR's libraries
// load with it, when a run first writes or reads an EXR (io/exr.cpp opens it), not at every
// start. It reads glint's ExrLayers and returns bytes, or reads a file's RGB; or a message: no
// exception crosses the boundary.
#include "io/exr.h"

#include <ImfChannelList.h>
#include <ImfCompressionAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <ImfStdIO.h>

#include <stdexcept>

namespace glint {

namespace {

// A FLOAT channel read from `base` with `stride` floats between pixels.
void add_float(Imf::Header& header, Imf::FrameBuffer& buffer, const char* name, const float* base,
               std::size_t stride, int width) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    const std::size_t x_stride = stride * sizeof(float);
    buffer.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(base)),
                                   x_stride, x_stride * static_cast<std::size_t>(width)));
}

void check_size(std::size_t size, std::size_t expected, const char* layer) {
    if (size != expected)
        throw std::runtime_error(std::string("EXR: the ") + layer + " layer has " +
                                 std::to_string(size) + " values, not " + std::to_string(expected));
}

std::string encoded(const ExrLayers& layers) {
    if (!layers.colour || layers.colour->empty())
        throw std::runtime_error("EXR: no colour to write");
    const FloatImage& colour = *layers.colour;
    const int width = colour.width, height = colour.height;
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    Imf::Header header(width, height);
    // ZIP: lossless, and the compression OpenEXR's own tools write by default for renders.
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer buffer;
    const float* rgb = colour.rgb.data();
    add_float(header, buffer, "R", rgb, 3, width);
    add_float(header, buffer, "G", rgb + 1, 3, width);
    add_float(header, buffer, "B", rgb + 2, 3, width);
    if (layers.depth) {
        check_size(layers.depth->size(), pixels, "depth");
        add_float(header, buffer, "Z", layers.depth->data(), 1, width);
    }
    if (layers.normal) {
        check_size(layers.normal->size(), 3 * pixels, "normal");
        const float* n = layers.normal->data();
        add_float(header, buffer, "N.X", n, 3, width);
        add_float(header, buffer, "N.Y", n + 1, 3, width);
        add_float(header, buffer, "N.Z", n + 2, 3, width);
    }
    if (layers.id) {
        check_size(layers.id->size(), pixels, "id");
        header.channels().insert("id", Imf::Channel(Imf::UINT));
        const std::size_t x_stride = sizeof(std::uint32_t);
        buffer.insert(
            "id", Imf::Slice(Imf::UINT,
                             reinterpret_cast<char*>(const_cast<std::uint32_t*>(layers.id->data())),
                             x_stride, x_stride * static_cast<std::size_t>(width)));
    }
    if (layers.cutoff) {
        check_size(layers.cutoff->size(), pixels, "cutoff");
        add_float(header, buffer, "cutoff", layers.cutoff->data(), 1, width);
    }
    try {
        Imf::StdOSStream stream;
        {
            // The file's offset table is written when it closes: read the stream after.
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(buffer);
            file.writePixels(height);
        }
        return stream.str();
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("OpenEXR: ") + e.what());
    }
}

} // namespace

} // namespace glint

// The entry io/exr.cpp looks up: the file for `layers` into `out`, true; or false with the
// message (the one encode_exr throws) in `error`.
extern "C" __attribute__((visibility("default"))) bool
glint_encode_exr(const glint::ExrLayers* layers, std::string* out, std::string* error) noexcept {
    try {
        *out = glint::encoded(*layers);
        return true;
    } catch (const std::exception& e) {
        *error = e.what();
    } catch (...) {
        *error = "EXR: the encoder failed";
    }
    return false;
}

// The other entry: the RGB of the EXR file at `path` (its R, G and B, or its Y as grey; alpha
// dropped) into `rgb`, width × height × 3 floats top row first, true; or false with the message.
extern "C" __attribute__((visibility("default"))) bool
glint_decode_exr(const char* path, int* width, int* height, std::vector<float>* rgb,
                 std::string* error) noexcept {
    try {
        Imf::RgbaInputFile file(path);
        const Imath::Box2i window = file.dataWindow();
        const long w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
        if (w < 1 || h < 1 || w > 65536 || h > 65536 || w * h > (1l << 28))
            throw std::runtime_error("its data window is " + std::to_string(w) + "x" +
                                     std::to_string(h) + " (at most 65536 a side, 2^28 pixels)");
        std::vector<Imf::Rgba> pixels(static_cast<std::size_t>(w * h));
        file.setFrameBuffer(pixels.data() - window.min.x - window.min.y * w, 1,
                            static_cast<std::size_t>(w));
        file.readPixels(window.min.y, window.max.y);
        rgb->resize(pixels.size() * 3);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            (*rgb)[3 * i] = pixels[i].r;
            (*rgb)[3 * i + 1] = pixels[i].g;
            (*rgb)[3 * i + 2] = pixels[i].b;
        }
        *width = static_cast<int>(w), *height = static_cast<int>(h);
        return true;
    } catch (const std::exception& e) {
        *error = e.what();
    } catch (...) {
        *error = "the decoder failed";
    }
    return false;
}
