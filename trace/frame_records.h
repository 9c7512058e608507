// The field lists of a frame's counters and figures (trace/record.h): the one place their names
// are spelled, read by the MPI ranks' records (app/rank_records.h) and by every JSON output that
// writes them (frame/record_json.h: render's --stats, compare's --json, explain's --json).
#pragma once

#include "trace/image_metrics.h"
#include "trace/primary_hits.h"
#include "trace/record.h"
#include "trace/render_result.h"

namespace glint {

template <> struct RecordFields<RayCounts> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("primary", r.primary), v("shadow", r.shadow), v("reflection", r.reflection);
        v("transmission", r.transmission);
    }
};

template <> struct RecordFields<PrimaryStats> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("exact_intersections", r.exact_intersections), v("fallbacks", r.fallbacks);
        v("corrected", r.corrected), v("edges", r.edges), v("checked", r.checked);
        v("tests", r.tests), v("traced", r.traced);
    }
};

template <> struct RecordFields<PhaseTimes> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("prepare", r.prepare), v("context", r.context), v("compile", r.compile);
        v("upload", r.upload), v("raster", r.raster), v("primary", r.primary);
        v("shading", r.shading), v("overlapped", r.overlapped);
    }
};

template <> struct RecordFields<ImageDifference> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("psnr_db", r.psnr_db), v("max_abs_error", r.max_abs_error);
        v("fraction_over_one", r.fraction_over_one), v("pixels_over_one", r.pixels_over_one);
        v("fraction_over_two", r.fraction_over_two);
        v("rmse", r.rmse), v("max_radiance_error", r.max_radiance_error);
    }
};

} // namespace glint
