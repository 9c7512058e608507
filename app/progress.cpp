#include "app/progress.h"

#include <cstdio>
#include <unistd.h>

namespace glint {

Progress::Progress(std::string label, int total, const std::atomic<int>& done)
    : label_(std::move(label)), total_(total), done_(done) {
    if (isatty(STDERR_FILENO)) thread_ = std::thread([this] { run(); });
}

Progress::~Progress() {
    if (!thread_.joinable()) return;
    {
        const std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

void Progress::run() {
    bool shown = false;
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stop_; })) {
        const double elapsed = watch_.seconds();
        if (elapsed < 1.0) continue;
        const double fraction = static_cast<double>(done_.load(std::memory_order_relaxed)) / total_;
        if (fraction > 0)
            std::fprintf(stderr, "\r%s %3.0f%%  %.1f s, about %.1f s left ", label_.c_str(),
                         100 * fraction, elapsed, elapsed * (1 - fraction) / fraction);
        else
            std::fprintf(stderr, "\r%s   0%%  %.1f s ", label_.c_str(), elapsed);
        std::fflush(stderr);
        shown = true;
    }
    if (shown) std::fprintf(stderr, "\r\033[K"); // leave the terminal line clean
}

} // namespace glint
