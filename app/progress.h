// Progress for long work on a terminal: silent when stderr is not a terminal, and for work that
// finishes within a second.
#pragma once

#include "trace/stopwatch.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace glint {

class Progress {
  public:
    // Reports `done` out of `total` under `label` until destroyed.
    Progress(std::string label, int total, const std::atomic<int>& done);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

  private:
    void run();

    std::string label_;
    int total_;
    const std::atomic<int>& done_;
    Stopwatch watch_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread thread_;
};

} // namespace glint
