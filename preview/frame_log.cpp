#include "preview/frame_log.h"

#include <algorithm>
#include <cstdio>

namespace glint {

double FrameLog::percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

void FrameLog::print() const {
    const auto over = std::count_if(frames.begin(), frames.end(), [](double t) { return t > 100; });
    std::printf("UI thread: start-up %.0f ms + first frame %.0f ms; then %zu frames, median "
                "%.1f ms, 99th percentile %.1f "
                "ms, max %.1f ms, "
                "%td over 100 ms; %zu trace restarts (camera or setting changes), median %.1f "
                "ms, max %.1f ms, of which the world median %.1f ms (at start-up %.1f ms)\n",
                start_up, first_frame, frames.size(), percentile(frames, 0.5),
                percentile(frames, 0.99), percentile(frames, 1.0), over, restarts.size(),
                percentile(restarts, 0.5), percentile(restarts, 1.0), percentile(worlds, 0.5),
                first_world);
}

} // namespace glint
