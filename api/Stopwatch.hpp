#pragma once
// Timings for the reports of the API and the commands, all measured one way: wall-clock
// seconds on the steady clock.
#include <chrono>

namespace dfrecon {

using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`. O(1).
inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Times a command and its stages: lap() gives the seconds of the stage
/// that just ended and starts the next, total() the seconds since the
/// watch was made. O(1) each.
class Stopwatch {
  public:
    double lap() {
        const Clock::time_point now = Clock::now();
        const double seconds = std::chrono::duration<double>(now - lapStart_).count();
        lapStart_ = now;
        return seconds;
    }
    /// Starts a stage without reporting the time since the last one.
    void restartLap() { lapStart_ = Clock::now(); }
    double total() const { return secondsSince(start_); }

  private:
    Clock::time_point start_ = Clock::now();
    Clock::time_point lapStart_ = start_;
};

}  // namespace dfrecon
