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
#include <exception>
#include <system_error>
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

/// Runs work(worker, stop) on the calling thread as worker 0 and on up to
/// `helpersWanted` more threads, workers 1, 2, ..., one per core the budget
/// has free, and returns when every worker has returned: how many helpers
/// ran. The workers share the work themselves (taking items from a common
/// counter, say). An exception thrown by a worker sets `stop`, which
/// workers that loop over items should check, and is rethrown here once all
/// have returned (the lowest worker's first); a thread that cannot be
/// started leaves the work to those that were. O(helpers) threads.
template <class Work>
std::size_t runOnFreeCores(std::size_t helpersWanted, Work&& work) {
    const CoreLease lease(helpersWanted);
    std::atomic<bool> stop{false};
    std::vector<std::exception_ptr> errors(lease.granted() + 1);
    auto run = [&](std::size_t worker) {
        try {
            work(worker, static_cast<const std::atomic<bool>&>(stop));
        } catch (...) {
            errors[worker] = std::current_exception();
            stop = true;
        }
    };
    std::vector<std::thread> helpers;
    for (std::size_t h = 1; h <= lease.granted(); ++h) {
        try {
            helpers.emplace_back(run, h);
        } catch (const std::system_error&) {
            break;  // no thread to be had: the workers started do the work
        }
    }
    run(0);
    for (std::thread& helper : helpers) helper.join();
    for (const std::exception_ptr& error : errors)
        if (error) std::rethrow_exception(error);
    return helpers.size();
}

/// The helpers a step of `items` independent items wants: one fewer than
/// the hardware threads, or none below `parallelFrom` items or with fewer
/// than two items.
inline std::size_t helpersFor(std::size_t items, std::size_t parallelFrom) {
    if (items < 2 || items < parallelFrom) return 0;
    return std::min<std::size_t>(items, std::max(1u, std::thread::hardware_concurrency())) - 1;
}

/// Calls body(i) for every i in [0, count): on the calling thread, and on
/// the cores left free when there are at least `parallelFrom` items, in
/// chunks taken in order. body must be safe to run at once for different
/// i (each writing only its own results), so that the outcome does not
/// depend on the threads; an exception from body is rethrown here after
/// the other threads stopped taking chunks. O(count) calls.
template <class Body>
void forEachOnFreeCores(std::size_t count, std::size_t parallelFrom, Body&& body) {
    constexpr std::size_t kChunk = 256;
    const std::size_t chunks = (count + kChunk - 1) / kChunk;
    std::atomic<std::size_t> next{0};
    runOnFreeCores(count < parallelFrom ? 0 : helpersFor(chunks, 2),
                   [&](std::size_t, const std::atomic<bool>& stop) {
                       for (std::size_t c; !stop && (c = next++) < chunks;)
                           for (std::size_t i = c * kChunk, end = std::min(count, i + kChunk);
                                i < end; ++i)
                               body(i);
                   });
}

}  // namespace dfrecon
