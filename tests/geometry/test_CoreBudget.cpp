// The process's core budget: workers on the free cores share the work, an
// exception in any of them reaches the caller (never std::terminate), and
// cores held elsewhere are not used twice.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "geometry/CoreBudget.hpp"

namespace dfrecon {
namespace {

std::size_t hardwareThreads() {
    return std::max(1u, std::thread::hardware_concurrency());
}

TEST(CoreBudget, WorkersShareTheItemsAndNoItemRunsTwice) {
    std::vector<std::atomic<int>> runs(10000);
    std::atomic<std::size_t> next{0};
    const std::size_t helpers =
        runOnFreeCores(helpersFor(runs.size(), 2), [&](std::size_t, const std::atomic<bool>&) {
            for (std::size_t i; (i = next++) < runs.size();) ++runs[i];
        });
    EXPECT_EQ(helpers, hardwareThreads() - 1);
    for (const std::atomic<int>& r : runs) ASSERT_EQ(r.load(), 1);
    std::vector<int> seen(5000, 0);
    forEachOnFreeCores(seen.size(), 1, [&](std::size_t i) { ++seen[i]; });
    for (int s : seen) ASSERT_EQ(s, 1);
}

TEST(CoreBudget, AnExceptionInAnyWorkerReachesTheCallerAfterAllStopped) {
    // Each worker throws in turn, the calling thread's (worker 0) among
    // them; the others see `stop` or run out of items, and all return
    // before the exception reaches here.
    for (std::size_t thrower = 0; thrower < hardwareThreads(); ++thrower) {
        std::atomic<std::size_t> running{0}, next{0};
        EXPECT_THROW(runOnFreeCores(hardwareThreads() - 1,
                                    [&](std::size_t worker, const std::atomic<bool>& stop) {
                                        ++running;
                                        if (worker == thrower)
                                            throw std::runtime_error("worker failed");
                                        while (!stop && next++ < 100000000) {
                                        }
                                        --running;
                                    }),
                     std::runtime_error);
        EXPECT_EQ(running.load(), 1u);  // only the thrower left without counting down
    }
    std::vector<int> seen(2000, 0);
    EXPECT_THROW(forEachOnFreeCores(seen.size(), 1,
                                    [&](std::size_t i) {
                                        if (i == 1500) throw std::logic_error("item failed");
                                        ++seen[i];
                                    }),
                 std::logic_error);
}

TEST(CoreBudget, CoresHeldElsewhereAreNotLentAgain) {
    const CoreLease all(hardwareThreads());
    EXPECT_EQ(all.granted(), hardwareThreads());
    std::atomic<int> workers{0};
    EXPECT_EQ(runOnFreeCores(8, [&](std::size_t, const std::atomic<bool>&) { ++workers; }), 0u);
    EXPECT_EQ(workers.load(), 1);  // the calling thread alone
    const CoreLease none(1);
    EXPECT_EQ(none.granted(), 0u);
}

}  // namespace
}  // namespace dfrecon
