#pragma once
// Stage timings for the commands' reports.
#include <chrono>

namespace dfrecon::app {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace dfrecon::app
