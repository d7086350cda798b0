#pragma once
// Items worked on by several threads, their results taken in item order: a
// command that reconstructs many ROIs keeps both cores busy yet prints its
// lines and report exactly as a run one ROI after the other would.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <type_traits>
#include <vector>

#include "geometry/CoreBudget.hpp"

namespace dfrecon {

/// The worker count a command uses by default: one per hardware thread, at
/// most one per item, at least one.
inline std::size_t defaultJobs(std::size_t items) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return std::max<std::size_t>(1, std::min(cores, items));
}

/// The workers for `items` when the user asked for `asked` (--jobs; 0: the
/// default): at most one per item and one per core (more threads than cores
/// only share them, each with its OpenCL queue and scratch), at least one.
inline std::size_t jobsFor(unsigned asked, std::size_t items) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return asked > 0 ? std::max<std::size_t>(1, std::min<std::size_t>({asked, items, cores}))
                     : defaultJobs(items);
}

/// Calls `work(item, worker)` for every item in [0, count) on `jobs` threads
/// (worker in [0, jobs) says which thread, so each can keep its own state,
/// e.g. an OpenCL queue), and `take(item, result)` on the calling thread in
/// item order as results become ready. With jobs <= 1 everything runs on
/// the calling thread, one item after the other. If `work` throws for an
/// item, no new items start, the items before it are still taken, and the
/// exception is rethrown in its place; an exception from `take` likewise
/// stops the workers. Items already under way when that happens finish
/// first (and their results are dropped).
template <class Work, class Take>
void forEachInOrder(std::size_t count, std::size_t jobs, Work work, Take take) {
    if (jobs <= 1 || count <= 1) {
        for (std::size_t item = 0; item < count; ++item) take(item, work(item, std::size_t(0)));
        return;
    }
    using Result = std::invoke_result_t<Work&, std::size_t, std::size_t>;
    struct Slot {
        std::optional<Result> result;
        std::exception_ptr error;
        bool done = false;
    };
    std::vector<Slot> slots(count);
    std::mutex mutex;
    std::condition_variable ready;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};

    auto run = [&](std::size_t worker) {
        // Each worker holds a core while it has items, so the steps inside
        // one (the mesh check) split only over cores no worker holds.
        const CoreLease core(1);
        for (std::size_t item; !stop && (item = next++) < count;) {
            Slot finished;
            try {
                finished.result.emplace(work(item, worker));
            } catch (...) {
                finished.error = std::current_exception();
                stop = true;
            }
            finished.done = true;
            {
                const std::lock_guard<std::mutex> lock(mutex);
                slots[item] = std::move(finished);
            }
            ready.notify_all();
        }
    };
    std::vector<std::thread> threads;
    // Joined on every way out, so no worker outlives the slots it writes.
    struct Joiner {
        std::vector<std::thread>& threads;
        std::atomic<bool>& stop;
        ~Joiner() {
            stop = true;
            for (std::thread& t : threads) t.join();
        }
    } joiner{threads, stop};
    for (std::size_t w = 0; w < std::min(jobs, count); ++w) threads.emplace_back(run, w);

    for (std::size_t item = 0; item < count; ++item) {
        Slot slot;
        {
            std::unique_lock<std::mutex> lock(mutex);
            ready.wait(lock, [&] { return slots[item].done; });
            slot = std::move(slots[item]);
        }
        if (slot.error) std::rethrow_exception(slot.error);
        take(item, std::move(*slot.result));
    }
}

}  // namespace dfrecon
