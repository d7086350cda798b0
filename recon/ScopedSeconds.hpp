#pragma once
// A stage's seconds, counted by scope: the reconstruction's stats add up
// the time of stages that are entered many times (a slab's fields and
// medial axes at every level of the recursion) without a start and a stop
// written around each.
#include <chrono>

namespace dfrecon {

/// Adds the seconds from its construction to its destruction to `into`.
class ScopedSeconds {
  public:
    explicit ScopedSeconds(double& into) : into_(into), start_(Clock::now()) {}
    ~ScopedSeconds() { into_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
    ScopedSeconds(const ScopedSeconds&) = delete;
    ScopedSeconds& operator=(const ScopedSeconds&) = delete;

  private:
    using Clock = std::chrono::steady_clock;
    double& into_;
    Clock::time_point start_;
};

}  // namespace dfrecon
