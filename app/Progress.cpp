#include "app/Progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace dfrecon::app {

Progress::Progress(std::string label, bool enabled)
    : label_(std::move(label)), active_(enabled && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() {
    finish();
}

void Progress::update(double fraction) {
    if (!active_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100) && fraction < 1) return;
    lastDraw_ = now;
    drawn_ = true;
    constexpr int kWidth = 30;
    const int filled = int(std::clamp(fraction, 0.0, 1.0) * kWidth);
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label_.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(),
                 int(std::clamp(fraction, 0.0, 1.0) * 100));
    std::fflush(stderr);
}

void Progress::finish() {
    if (!active_ || !drawn_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
}

}  // namespace dfrecon::app
