#include "io/environment_file.h"

#include "io/error.h"
#include "io/exr.h"
#include "io/read_text.h"

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

namespace glint {

namespace {

// A smooth step from 0 at `edge0` to 1 at `edge1`.
double smooth(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// A soft rectangular panel of light centred at azimuth `az` and elevation `el` (radians), with
// half-sizes `half_az` and `half_el`: 1 inside, fading to 0 over a tenth of its size.
double panel(double azimuth, double elevation, double az, double el, double half_az,
             double half_el) {
    double da = std::remainder(azimuth - az, 2 * std::numbers::pi);
    const double de = elevation - el;
    return (1 - smooth(half_az * 0.8, half_az, std::abs(da))) *
           (1 - smooth(half_el * 0.8, half_el, std::abs(de)));
}

} // namespace

std::shared_ptr<const Environment> studio_environment() {
    static const std::shared_ptr<const Environment> made = [] {
        auto studio = std::make_shared<Environment>();
        studio->name = kStudioEnvironment;
        studio->width = 256, studio->height = 128;
        studio->rgb.resize(static_cast<std::size_t>(studio->width) * studio->height * 3);
        const double pi = std::numbers::pi;
        for (int j = 0; j < studio->height; ++j)
            for (int i = 0; i < studio->width; ++i) {
                // The direction of the texel's centre, by DESIGN §14's formula read backwards:
                // azimuth 0 looks down −Z (ahead of a camera on +Z), positive towards +X.
                const double u = (i + 0.5) / studio->width, v = (j + 0.5) / studio->height;
                const double azimuth = (u - 0.5) * 2 * pi, elevation = pi / 2 - v * pi;
                // Walls from 0.6 at the horizon to 0.8 overhead; a floor of 0.25.
                const double wall = 0.6 + 0.2 * std::sin(std::max(elevation, 0.0));
                double radiance = 0.25 + (wall - 0.25) * smooth(-0.05, 0.05, elevation);
                // The camera's view of a model is lit from behind it: the panels stand around
                // +Z (azimuth ±π), to the left and right, and one overhead.
                radiance += 3.0 * panel(azimuth, elevation, pi - 0.9, 0.45, 0.35, 0.25);
                radiance += 2.0 * panel(azimuth, elevation, -pi + 0.9, 0.45, 0.35, 0.25);
                radiance += 1.5 * panel(azimuth, elevation, 0, 1.35, pi, 0.2);
                float* p = &studio->rgb[(static_cast<std::size_t>(j) * studio->width + i) * 3];
                p[0] = p[1] = p[2] = static_cast<float>(radiance);
                studio->brightest = glm::max(studio->brightest, glm::vec3(p[0]));
            }
        return std::shared_ptr<const Environment>(std::move(studio));
    }();
    return made;
}

std::shared_ptr<const Environment> load_environment(const std::string& spec,
                                                    const std::filesystem::path& base,
                                                    const std::string& where) {
    if (spec == kStudioEnvironment) return studio_environment();
    const std::filesystem::path given(spec);
    const std::filesystem::path path = given.is_absolute() ? given : base / given;
    const std::string named = where + ": " + printable(path.string(), std::string::npos);
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    auto out = std::make_shared<Environment>();
    out->name = path.string();
    if (extension == ".hdr") {
        const std::string bytes = read_scene_file(path, "environment");
        const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
        const int size = static_cast<int>(std::min<std::size_t>(bytes.size(), INT32_MAX));
        if (!stbi_is_hdr_from_memory(data, size))
            throw SceneError(named + ": not a Radiance .hdr image");
        int channels = 0;
        const std::unique_ptr<float, void (*)(void*)> pixels(
            stbi_loadf_from_memory(data, size, &out->width, &out->height, &channels, 3),
            stbi_image_free);
        if (!pixels) throw SceneError(named + ": cannot be decoded: " + stbi_failure_reason());
        out->rgb.assign(pixels.get(),
                        pixels.get() + static_cast<std::size_t>(out->width) * out->height * 3);
    } else if (extension == ".exr") {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) throw SceneError(named + ": no such file");
        try {
            ExrRgb exr = read_exr_rgb(path);
            out->width = exr.width, out->height = exr.height, out->rgb = std::move(exr.rgb);
        } catch (const std::runtime_error& e) {
            throw SceneError(named + ": cannot be read as OpenEXR: " + e.what());
        }
    } else {
        throw SceneError(named + ": an environment is an equirectangular .hdr or .exr file, or '" +
                         kStudioEnvironment + "'");
    }
    if (out->width < 1 || out->height < 1) throw SceneError(named + ": the image has no pixels");
    for (std::size_t i = 0; i < out->rgb.size(); ++i) {
        auto& brightest = out->brightest[static_cast<int>(i % 3)];
        brightest = std::max(brightest, out->rgb[i]);
        if (!(out->rgb[i] >= 0 && out->rgb[i] <= kMaxColour)) {
            const std::size_t pixel = i / 3;
            throw SceneError(named + ": texel (" + std::to_string(pixel % out->width) + ", " +
                             std::to_string(pixel / out->width) +
                             ") has a radiance that is negative, not finite or above 1e6");
        }
    }
    return out;
}

} // namespace glint
