// What one render measured, as `glint render` reports it and --stats writes it, and as the
// Python module's Frame.stats gives it (python/): one definition for both.
#pragma once

#include "app/options.h"
#include "app/rank_records.h"
#include "trace/cutoff.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace glint {

struct RenderReport {
    std::filesystem::path scene_path;
    std::filesystem::path output; // empty: none written (the Python module)
    const Scene& scene;
    const FrameOptions& frame_options;
    const World& world;
    const Frame& frame;
    CutoffBound cutoff;
    int threads;
    double load_seconds, prepare_seconds, write_seconds, total_seconds;
    // Under mpirun, on rank 0: each rank's figures (its exchanges per kind of pass among them).
    std::vector<RankFigures> ranks = {};
};

// The --stats file: settings, seconds per phase, rays, cut-off, structure, hybrid figures. The
// structure's traversal figures count only where the World counted them (count_traversals).
nlohmann::ordered_json stats_json(const RenderReport& r);

} // namespace glint
