#pragma once
// Wall-clock timing for benchmarks: the best of several runs, in seconds.
#include <algorithm>
#include <chrono>

namespace dfrecon::bench {

template <class F>
double bestSeconds(int runs, F&& work) {
    double best = 1e300;
    for (int r = 0; r < runs; ++r) {
        const auto start = std::chrono::steady_clock::now();
        work();
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        best = std::min(best, elapsed.count());
    }
    return best;
}

}  // namespace dfrecon::bench
