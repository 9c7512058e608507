// The one timer: wall time (a steady clock) in seconds, for every phase glint reports.
#pragma once

#include <chrono>

namespace glint {

class Stopwatch {
  public:
    using Clock = std::chrono::steady_clock;

    // Seconds since construction or the last restart.
    double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    double milliseconds() const { return 1e3 * seconds(); }
    // Seconds since the start; then starts again from now.
    double lap() {
        const Clock::time_point now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return elapsed;
    }
    void restart() { start_ = Clock::now(); }

  private:
    Clock::time_point start_ = Clock::now();
};

// Runs `work` and adds its wall time to `seconds` (also when it throws); returns what it returns.
template <class Work> auto timed(double& seconds, const Work& work) {
    struct Add {
        double& seconds;
        Stopwatch watch;
        ~Add() { seconds += watch.seconds(); }
    } add{seconds, {}};
    return work();
}

} // namespace glint
