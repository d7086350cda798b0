// forEachInOrder: results taken in item order whatever order workers finish
// in, every item once, errors rethrown in their place.
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <stdexcept>
#include <thread>

#include "geometry/OrderedParallel.hpp"

using dfrecon::forEachInOrder;

TEST(OrderedParallel, TakesResultsInItemOrder) {
    for (std::size_t jobs : {1u, 2u, 3u, 8u}) {
        std::vector<std::size_t> taken;
        std::set<std::size_t> workers;
        std::mutex mutex;
        forEachInOrder(
            20, jobs,
            [&](std::size_t item, std::size_t worker) {
                {
                    const std::lock_guard<std::mutex> lock(mutex);
                    workers.insert(worker);
                }
                // Early items slowest, so later ones finish first.
                std::this_thread::sleep_for(std::chrono::milliseconds(20 - item));
                return item * item;
            },
            [&](std::size_t item, std::size_t square) {
                EXPECT_EQ(square, item * item);
                taken.push_back(item);
            });
        ASSERT_EQ(taken.size(), 20u) << jobs;
        for (std::size_t k = 0; k < taken.size(); ++k) EXPECT_EQ(taken[k], k);
        for (std::size_t w : workers) EXPECT_LT(w, jobs);
    }
}

TEST(OrderedParallel, AnErrorStopsNewItemsAndIsRethrownInPlace) {
    for (std::size_t jobs : {1u, 2u, 4u}) {
        std::vector<std::size_t> taken;
        std::atomic<std::size_t> started{0};
        EXPECT_THROW(forEachInOrder(
                         100, jobs,
                         [&](std::size_t item, std::size_t) {
                             ++started;
                             if (item == 5) throw std::runtime_error("item 5");
                             std::this_thread::sleep_for(std::chrono::milliseconds(2));
                             return item;
                         },
                         [&](std::size_t item, std::size_t) { taken.push_back(item); }),
                     std::runtime_error);
        // Everything before the failing item is taken, nothing after it.
        ASSERT_EQ(taken.size(), 5u) << jobs;
        // The others finish the items they hold (a few ms each) and stop.
        EXPECT_LT(started.load(), 50u) << jobs;
    }
}
