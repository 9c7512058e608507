// The settings `glint tradeoff` sweeps for a scene: each knob varied alone from the default.
#include "app/tradeoff.h"

#include "io/error.h"

#include <cstdio>
#include <map>

namespace glint {
namespace tradeoff {

std::string format_threshold(float threshold) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(threshold));
    return text;
}

std::vector<std::pair<std::string, Setting>> sweep(const Scene& scene, int samples) {
    Setting hybrid;
    hybrid.max_depth = scene.render.max_depth;
    hybrid.min_reflectivity = scene.render.min_reflectivity;
    Setting ray = hybrid;
    ray.frame.mode = Mode::ray;
    std::vector<std::pair<std::string, Setting>> out;
    const auto add = [&](const char* knob, Setting s) { out.emplace_back(knob, s); };
    add("mode", hybrid);
    add("mode", ray);
    for (const Resolve resolve : {Resolve::exact, Resolve::trust}) {
        Setting s = hybrid;
        s.frame.resolve = resolve;
        for (const int tess : {4, 8, 16, 32, 64}) {
            s.frame.tessellation = tess;
            add(resolve == Resolve::exact ? "tessellation" : "resolve", s);
        }
        s.frame.tessellation = kDefaultTessellation;
        for (const RasterMode raster : {RasterMode::mesh, RasterMode::proxy}) {
            s.frame.raster = raster;
            add("raster", s);
        }
    }
    for (int depth = 0; depth <= 8; ++depth) {
        Setting s = ray;
        s.max_depth = depth;
        add("max_depth", s);
    }
    for (const float cutoff : {0.0f, 0.001f, 0.01f, 0.03f, 0.1f}) {
        Setting s = ray;
        s.min_reflectivity = cutoff;
        add("min_reflectivity", s);
    }
    for (const AccelKind kind : all_values<AccelKind>()) {
        Setting s = ray;
        s.accel = kind;
        add("accel", s);
    }
    for (const int divisor : {2, 4}) {
        Setting s = ray;
        s.divisor = divisor;
        add("resolution", s);
    }
    Setting precise = ray;
    precise.frame.precision = Precision::f64;
    add("precision", precise);
    // The exact image's own setting in float: what double precision alone adds.
    Setting untruncated = ray;
    untruncated.max_depth = kMaxDepth;
    untruncated.min_reflectivity = 0;
    add("precision", untruncated);
    // Antialiasing, in the default (hybrid) mode, against the uniform 8×8 image: uniform grids
    // up to --samples, then adaptive at that grid over the threshold.
    Setting grid = hybrid;
    grid.against_grid = true;
    for (int n = 1; n <= samples; ++n) {
        grid.samples = n;
        add("samples", grid);
    }
    grid.samples = samples;
    grid.antialias = Antialias::adaptive;
    for (const float threshold : {0.005f, 0.01f, 0.02f, 0.05f, 0.1f}) {
        grid.aa_threshold = threshold;
        add("aa_threshold", grid);
    }
    return out;
}

} // namespace tradeoff
} // namespace glint
