#include "cl/HostScratch.hpp"

#include <cstdint>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace dfrecon::ocl {
namespace {

constexpr std::size_t kLarge = kScratchPooledFrom * 4;

TEST(HostScratch, AGivenBackBlockServesTheNextRequestOfItsSize) {
    releaseScratch();
    void* first = takeScratch(kLarge);
    giveScratch(first, kLarge);
    EXPECT_EQ(keptScratchBytes(), kLarge);
    void* second = takeScratch(kLarge);
    EXPECT_EQ(second, first);
    EXPECT_EQ(keptScratchBytes(), 0u);
    giveScratch(second, kLarge);
    releaseScratch();
    EXPECT_EQ(keptScratchBytes(), 0u);
}

TEST(HostScratch, ALargerKeptBlockServesOnlyRequestsAtLeastTwoThirdsOfIt) {
    releaseScratch();
    void* block = takeScratch(kLarge);
    giveScratch(block, kLarge);
    // A kept block of kLarge serves ⌈kLarge·2/3⌉ (it is at most half as
    // large again) but not kLarge/2.
    void* half = takeScratch(kLarge / 2);
    EXPECT_NE(half, block);
    const std::size_t twoThirdsBytes = (kLarge * 2 + 2) / 3;
    void* twoThirds = takeScratch(twoThirdsBytes);
    EXPECT_EQ(twoThirds, block);
    // Given back with the size asked for, it is kept with its own size.
    giveScratch(twoThirds, twoThirdsBytes);
    giveScratch(half, kLarge / 2);
    EXPECT_EQ(keptScratchBytes(), kLarge + kLarge / 2);
    releaseScratch();
}

TEST(HostScratch, SmallBlocksAreNotKeptAndBlocksAreAligned) {
    releaseScratch();
    void* small = takeScratch(100);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(small) % 64, 0u);
    giveScratch(small, 100);
    EXPECT_EQ(keptScratchBytes(), 0u);
    void* large = takeScratch(kLarge + 8);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large) % 64, 0u);
    giveScratch(large, kLarge + 8);
    releaseScratch();
}

TEST(HostScratch, KeepsNoMoreThanItsLimit) {
    releaseScratch();
    const std::size_t block = kScratchKeptBytes / 3;
    std::vector<void*> lent;
    for (int k = 0; k < 5; ++k) lent.push_back(takeScratch(block));
    for (void* p : lent) giveScratch(p, block);
    EXPECT_EQ(keptScratchBytes(), 3 * block);
    releaseScratch();
}

TEST(HostScratch, VectorsKeepTheirContentsAsTheyGrow) {
    ScratchVector<std::uint64_t> values;
    for (std::uint64_t k = 0; k < 100000; ++k) values.push_back(k * k);
    for (std::uint64_t k = 0; k < 100000; ++k) ASSERT_EQ(values[k], k * k);
    ScratchVector<std::uint64_t> moved = std::move(values);
    EXPECT_EQ(moved.size(), 100000u);
    EXPECT_EQ(moved[99999], 99999ull * 99999ull);
    ScratchArray<float> array(kLarge);
    array.data()[kLarge - 1] = 1;
    EXPECT_EQ(array.size(), kLarge);
}

TEST(HostScratch, ThreadsTakeAndGiveBackConcurrently) {
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([t] {
            for (int k = 0; k < 200; ++k) {
                const std::size_t bytes = kScratchPooledFrom * std::size_t(1 + (k + t) % 5);
                auto* p = static_cast<unsigned char*>(takeScratch(bytes));
                p[0] = p[bytes - 1] = static_cast<unsigned char>(t);
                EXPECT_EQ(p[0], t);
                giveScratch(p, bytes);
            }
        });
    for (std::thread& thread : threads) thread.join();
    EXPECT_LE(keptScratchBytes(), kScratchKeptBytes);
    releaseScratch();
}

}  // namespace
}  // namespace dfrecon::ocl
