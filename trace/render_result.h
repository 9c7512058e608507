// What a frame's trace gives back, the same type in either precision (trace/math.h): its float
// image, AOVs, ray counts and phase times. The double-precision tracer is the reference for the
// float one, in the tests and in `glint tradeoff`.
#pragma once

#include "trace/accel/accel_kind.h"
#include "trace/image.h"
#include "trace/image_metrics.h"
#include "trace/names.h"
#include "trace/scene.h"
#include "trace/tiles.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace glint {

struct RayCounts {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;
    std::uint64_t transmission = 0; // refracted rays, and totally internally reflected ones

    RayCounts& operator+=(const RayCounts& other) {
        primary += other.primary, shadow += other.shadow, reflection += other.reflection;
        transmission += other.transmission;
        return *this;
    }
    std::uint64_t total() const { return primary + shadow + reflection + transmission; }
};

// The primary hit of each pixel centre (DESIGN §12: §2's ray, whatever the sample grid), kept
// where a frame is asked for its AOVs (`glint render --aov`); per pixel, row-major, top row
// first. Hybrid and ray mode find the same hits, so they keep the same values.
struct PrimaryAovs {
    std::vector<float> depth;      // the hit's t: the distance from the eye; +inf for no hit
    std::vector<float> normal;     // 3 a pixel: unit world shading normal facing the eye; 0, 0, 0
    std::vector<std::uint32_t> id; // object index + 1; 0 where nothing is hit

    explicit PrimaryAovs(std::size_t pixels = 0)
        : depth(pixels, std::numeric_limits<float>::infinity()), normal(3 * pixels, 0.0f),
          id(pixels, 0) {}
    bool empty() const { return depth.empty(); }
};

// The pixels of one render, whichever mode and precision made them; per pixel, row-major, top
// row first. frame/frame.h's Frame wraps it with the phase times.
struct RenderResult {
    // Each pixel's colour, linear: the mean of its samples' unclamped colours (radiance above 1
    // survives; what an EXR holds).
    FloatImage radiance;
    // With N×N samples a pixel (N > 1): the mean of the samples' colours each clamped to [0, 1]
    // (DESIGN §11), what the PNG shows. Empty with one sample a pixel, where it is the radiance
    // clamped.
    FloatImage clamped;
    // Where the frame keeps no float image (FrameRequest::radiance false: a PNG render in one
    // process, which reads nothing else of it), each pixel's display bytes, to_byte of the value
    // display() would hold, made as the pixel is stored: 6 MB at 1920×1080 instead of 25 MB of
    // floats first touched. Then radiance and clamped are empty. Read it through byte_at.
    Image display_bytes;
    RayCounts rays;
    // The summed path weights of the reflected and transmitted rays that max_depth or
    // min_reflectivity kept from being cast, 0 where none was (trace/cutoff.h). Empty where no
    // material reflects or transmits (SceneGeometry::secondary), so every weight would be 0:
    // read it by omitted_at.
    FrameLayer<float> omitted_weight;
    // The primary hit's object index + 1, 0 for background: of the pixel centre, or with an
    // N×N grid of its sample (N/2, N/2) (the centre when N is odd). Empty where the frame was
    // not asked for them (FrameRequest::ids: `glint render` reads none).
    FrameLayer<std::uint32_t> ids;
    // Adaptive antialiasing only: 1 where the pixel took its N×N grid, 0 where its centre.
    std::vector<std::uint8_t> refined;
    // Where asked for: what the pixel centres' primary rays hit.
    PrimaryAovs aovs;
    // The tile loops the frame took: centres, grids, each round of adaptive spreading (on MPI
    // ranks, one exchange each).
    int passes = 0;

    // Pixel i's omitted weight, 0 where the frame keeps no such layer.
    float omitted_at(std::size_t i) const {
        return omitted_weight.empty() ? 0.0f : omitted_weight[i];
    }
    // Sets it, where the frame keeps the layer.
    void set_omitted(std::size_t i, float weight) {
        if (!omitted_weight.empty()) omitted_weight[i] = weight;
    }
    bool floats() const { return display_bytes.rgb.empty(); }
    int width() const { return floats() ? radiance.width : display_bytes.width; }
    int height() const { return floats() ? radiance.height : display_bytes.height; }
    std::size_t pixels() const { return static_cast<std::size_t>(width()) * height(); }

    // The colour a display shows, each channel clamped to [0, 1]; only where floats() (a frame
    // without them has its bytes alone).
    const FloatImage& display() const { return clamped.empty() ? radiance : clamped; }
    // The PNG's bytes: round(255·c) of the display colour (DESIGN §11).
    Image bytes() const { return floats() ? to_bytes(display()) : display_bytes; }
    // Channel c of pixel i's PNG byte.
    std::uint8_t byte_at(std::size_t i, int c) const {
        return floats() ? to_byte(display().rgb[3 * i + c]) : display_bytes.rgb[3 * i + c];
    }
};

// `test` against `reference`: their PNG bytes (PSNR, largest error, pixels off by more than
// 1/255 and 2/255), and their float images in radiance (RMSE, largest difference).
inline ImageDifference compare_results(const RenderResult& reference, const RenderResult& test) {
    ImageDifference diff = compare_images(reference.bytes(), test.bytes());
    add_radiance_error(diff, reference.radiance, test.radiance);
    return diff;
}

// Wall time of each phase of a frame, in seconds (trace/stopwatch.h).
struct PhaseTimes {
    double prepare = 0; // the World: transforms, bounds, structures (when the frame built it)
    double context = 0; // GL context creation
    double compile = 0; // shader compilation (first use; ~0.2 s on llvmpipe)
    double upload = 0;  // tessellation and buffer upload
    double raster = 0;  // drawing the item buffer and reading it back
    double primary = 0; // resolving primary hits (hybrid) or casting primary rays (ray)
    double shading = 0; // shading, shadow and reflection rays
    // Hybrid: the seconds of the GL pass (context, compile, upload, raster and the bins, each
    // counted in its phase above) that ran beside the World's preparation on the pass's own
    // thread (frame/gl_pass.h), so added nothing to the frame's wall time. 0 in ray mode.
    double overlapped = 0;

    double primary_visibility() const { return raster + primary; }
    // A loop that did both per tile took `wall` seconds: shared between primary and shading in
    // the ratio of its tiles' summed times for each.
    void add_split(double wall, double primary_busy, double shading_busy) {
        const double busy = primary_busy + shading_busy;
        const double primary_share = busy > 0 ? primary_busy / busy : 0;
        primary += wall * primary_share;
        shading += wall * (1 - primary_share);
    }
    // The frame's wall time: its phases, less what ran beside another.
    double total() const {
        return prepare + context + compile + upload + raster + primary + shading - overlapped;
    }
    // Per frame: the wall time less what the one-time GL set-up (context, shader compilation)
    // added to it, which a preview or a sweep pays once. The set-up runs on the GL pass's thread
    // beside the World's preparation, and `overlapped` counts what that hid: it came off the wall
    // time already (subtracting the set-up whole made a hidden one's frame negative).
    double per_frame() const { return total() - std::max(0.0, context + compile - overlapped); }
};

// A ray-mode render from the scene (World, primary rays, shading), timing its phases into
// `times`: the same function in each precision, one per library (glint_trace, glint_trace_f64).
// frame/frame.h's render_frame is the way in; this is what it calls for double precision.
inline namespace f32 {
RenderResult render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                              const TileProgress& progress, PhaseTimes& times);
}
inline namespace f64 {
RenderResult render_ray_frame(const Scene& scene, std::optional<AccelKind> accel,
                              const TileProgress& progress, PhaseTimes& times);
}

enum class Precision { f32, f64 };

template <> struct EnumNames<Precision> {
    static constexpr auto names = name_table("float", "double");
};

inline RenderResult render_ray_frame(Precision precision, const Scene& scene,
                                     std::optional<AccelKind> accel, const TileProgress& progress,
                                     PhaseTimes& times) {
    return precision == Precision::f64 ? f64::render_ray_frame(scene, accel, progress, times)
                                       : f32::render_ray_frame(scene, accel, progress, times);
}

} // namespace glint
