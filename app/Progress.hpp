#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal
// (and not --quiet), so logs and pipes stay clean.
#include <chrono>
#include <string>

namespace dfrecon::app {

class Progress {
  public:
    /// `enabled` is usually `!quiet`; the bar still stays off without a TTY.
    Progress(std::string label, bool enabled);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    /// Sets completion in [0, 1]; redraws at most ten times a second.
    void update(double fraction);
    /// Clears the line.
    void finish();

  private:
    std::string label_;
    bool active_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point lastDraw_{};
};

}  // namespace dfrecon::app
