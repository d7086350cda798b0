#pragma once
// The process's cores, shared between work split at two levels: a command
// that runs several ROIs at once holds a core per worker, and a step inside
// one ROI (the mesh check's pair search) borrows only the cores left over.
// Without it, two workers each splitting their check over both cores ran
// four threads on two and gained nothing; with it, the last ROI of a set,
// alone, still gets both.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace dfrecon {

/// Holds up to `wanted` cores of the process's budget (one per hardware
/// thread) while it lives; `granted()` says how many it got (0 when none
/// is free: the caller runs on its own thread, which it always may). Never
/// blocks. O(1).
class CoreLease {
  public:
    explicit CoreLease(std::size_t wanted) {
        std::ptrdiff_t free = freeCores().load();
        while (free > 0 && wanted > 0) {
            const std::ptrdiff_t take = std::min<std::ptrdiff_t>(free, std::ptrdiff_t(wanted));
            if (freeCores().compare_exchange_weak(free, free - take)) {
                granted_ = std::size_t(take);
                break;
            }
        }
    }
    ~CoreLease() { freeCores() += std::ptrdiff_t(granted_); }
    CoreLease(const CoreLease&) = delete;
    CoreLease& operator=(const CoreLease&) = delete;

    std::size_t granted() const { return granted_; }

  private:
    static std::atomic<std::ptrdiff_t>& freeCores() {
        static std::atomic<std::ptrdiff_t> cores{
            std::ptrdiff_t(std::max(1u, std::thread::hardware_concurrency()))};
        return cores;
    }
    std::size_t granted_ = 0;
};

/// Calls body(i) for every i in [0, count): on the calling thread, and on
/// the cores left free when there are at least `parallelFrom` items, in
/// chunks taken in order. body must be safe to run at once for different
/// i (each writing only its own results), so that the outcome does not
/// depend on the threads. O(count) calls.
template <class Body>
void forEachOnFreeCores(std::size_t count, std::size_t parallelFrom, Body&& body) {
    constexpr std::size_t kChunk = 256;
    const std::size_t chunks = (count + kChunk - 1) / kChunk;
    const std::size_t wanted =
        count < parallelFrom || chunks < 2
            ? 0
            : std::min<std::size_t>(chunks, std::max(1u, std::thread::hardware_concurrency())) - 1;
    const CoreLease lease(wanted);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t c; (c = next++) < chunks;)
            for (std::size_t i = c * kChunk, end = std::min(count, i + kChunk); i < end; ++i)
                body(i);
    };
    std::vector<std::thread> helpers;
    for (std::size_t h = 0; h < lease.granted(); ++h) helpers.emplace_back(work);
    work();
    for (std::thread& helper : helpers) helper.join();
}

}  // namespace dfrecon
