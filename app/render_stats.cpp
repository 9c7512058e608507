#include "app/render_stats.h"

#include "app/phase_json.h"
#include "frame/record_json.h"
#include "trace/frame_records.h"
#include "trace/kernel.h"

#include <algorithm>

namespace glint {

// The --stats file: settings, seconds per phase, rays, cut-off, structure, hybrid figures.
nlohmann::ordered_json stats_json(const RenderReport& r) {
    const Scene& scene = r.scene;
    const RayCounts& rays = r.frame.result.rays;
    const PhaseTimes& t = r.frame.times;
    nlohmann::ordered_json stats = {
        {"scene", r.scene_path.string()},
        {"output", r.output.empty() ? nlohmann::ordered_json(nullptr)
                                    : nlohmann::ordered_json(r.output.string())},
        {"width", scene.camera.width},
        {"height", scene.camera.height},
        {"mode", r.frame_options.mode},
        {"threads", r.threads},
        {"kernel", name_of(active_kernel())},
        {"max_depth", scene.render.max_depth},
        {"min_reflectivity", scene.render.min_reflectivity},
        {"samples", scene.render.samples},
        {"antialias", name_of(scene.render.antialias)},
        {"aa_threshold", scene.render.aa_threshold},
        {"packet_levels", scene.render.packet_levels},
        {"seconds", {{"load", r.load_seconds}, {"prepare", r.prepare_seconds}}},
        {"rays", record_json(rays)},
        {"cutoff",
         {{"bound_max_255", r.cutoff.max},
          {"pixels_over_1_255", r.cutoff.pixels_over_one},
          {"largest_omitted_weight", r.cutoff.largest_omitted_weight}}},
    };
    nlohmann::ordered_json& seconds = stats["seconds"];
    seconds.update(phase_seconds_json(t));
    seconds["frame"] = t.total(); // from the World to the last pixel, wall time
    seconds["write"] = r.write_seconds;
    seconds["total"] = r.total_seconds;
    // Per ray: over every query the tracer made (primary, shadow, reflected and transmitted
    // rays, and in hybrid mode the resolve's exact-interval queries, counted with the primary
    // rays).
    const TraversalCounters counts = r.world.traversal_counts();
    const double queries = static_cast<double>(rays.total());
    const Accelerator& accel = r.world.accelerator();
    stats["accel"] = {
        {"kind", name_of(accel.kind())},
        {"build_seconds", r.world.build_seconds()},
        {"memory_bytes", accel.memory_bytes()},
        {"nodes", accel.node_count()},
        {"nodes_visited_per_ray", static_cast<double>(counts.nodes) / queries},
        {"primitives_tested_per_ray", static_cast<double>(counts.primitives) / queries}};
    stats["passes"] = r.frame.result.passes;
    if (!r.ranks.empty()) {
        // The per-rank lines of the report; bytes and seconds of the exchanges by kind of pass.
        nlohmann::ordered_json& ranks = stats["ranks"] = nlohmann::ordered_json::array();
        for (const RankFigures& f : r.ranks) ranks.push_back(record_json(f));
    }
    if (!r.frame.result.refined.empty())
        stats["refined_pixels"] = std::count(r.frame.result.refined.begin(),
                                             r.frame.result.refined.end(), std::uint8_t{1});
    if (r.frame_options.settings().mode == Mode::hybrid) {
        const PrimaryStats& p = r.frame.primary_stats;
        const std::vector<float>& deviations = r.frame.deviations;
        stats["hybrid"] = {{"gl", r.frame_options.gl},
                           {"gl_renderer", r.frame.gl_renderer},
                           {"raster", r.frame_options.raster},
                           {"tessellation", r.frame_options.tessellation},
                           {"resolve", r.frame_options.resolve}};
        // The resolve's counters under their field names (trace/frame_records.h), as compare's
        // --json writes them.
        stats["hybrid"].update(record_json(p));
        stats["hybrid"].update(
            {{"proxy_objects", r.frame.proxies},
             {"tessellated_objects", r.frame.tessellated},
             {"max_deviation", deviations.empty()
                                   ? 0.0f
                                   : *std::max_element(deviations.begin(), deviations.end())}});
    }
    return stats;
}

} // namespace glint
