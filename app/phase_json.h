// The frame's phase times as JSON, as render's --stats and compare's --json both write them.
#pragma once

#include "trace/render_result.h"

#include <nlohmann/json.hpp>

namespace glint {

// {"context": …, "compile": …, "upload": …, "raster": …, "primary": …, "shading": …,
// "overlapped": …}, seconds: each phase's wall time, and how much of the GL pass's ran beside
// the World's preparation (PhaseTimes::overlapped).
inline nlohmann::ordered_json phase_seconds_json(const PhaseTimes& t) {
    return {{"context", t.context},      {"compile", t.compile}, {"upload", t.upload},
            {"raster", t.raster},        {"primary", t.primary}, {"shading", t.shading},
            {"overlapped", t.overlapped}};
}

} // namespace glint
