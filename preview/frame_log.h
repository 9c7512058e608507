// The preview's frame log: how long the UI thread worked each frame (between two waits for
// input, not the wait) and each restart of the trace, printed when the window closes
// (docs/PREVIEW.md, "Responsiveness").
#pragma once

#include <vector>

namespace glint {

// Frame times of the UI thread: the work between two waits for input, not the wait.
struct FrameLog {
    double start_up = 0;                  // the first item buffer and trace start, milliseconds
    double first_frame = 0;               // the first image on screen
    std::vector<double> frames, restarts; // milliseconds
    double first_world = 0;               // preparing the scene at start-up, milliseconds
    std::vector<double> worlds;           // of each restart: the camera-relative world

    // The value at fraction p (0 … 1) of the sorted values, 0 for none.
    static double percentile(std::vector<double> v, double p);
    void print() const;
};

} // namespace glint
