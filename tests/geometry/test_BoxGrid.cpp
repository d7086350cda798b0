// BoxGrid against brute force: every box that overlaps a query, once.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "geometry/BoxGrid.hpp"

namespace dfrecon {

TEST(BoxGrid, ListsExactlyTheOverlappingBoxesOnce) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> at(-20, 20), size(0, 3), big(0, 30);
    auto box = [&](bool large) {
        Box3 b;
        const Vec3 lo{at(random), at(random), at(random)};
        b.add(lo);
        b.add(lo + Vec3{large ? big(random) : size(random), size(random), size(random)});
        return b;
    };
    std::vector<Box3> boxes;
    for (int i = 0; i < 500; ++i) boxes.push_back(box(i % 50 == 0));
    const BoxGrid grid(boxes, 1.5);
    for (int q = 0; q < 200; ++q) {
        const Box3 query = box(q % 20 == 0);
        std::multiset<std::uint32_t> found;
        grid.overlapping(query, [&](std::uint32_t i) { found.insert(i); });
        std::multiset<std::uint32_t> expected;
        for (std::uint32_t i = 0; i < boxes.size(); ++i)
            if (boxes[i].overlaps(query)) expected.insert(i);
        EXPECT_EQ(found, expected) << q;
    }
    EXPECT_THROW(BoxGrid(boxes, 0), std::invalid_argument);
}

}  // namespace dfrecon
