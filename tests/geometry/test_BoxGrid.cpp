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
    // Cells of 5 mm make a dense grid (14 a side), of 1.5 and 0.4 mm a
    // sparse one (far more cells than boxes).
    for (const double cellMm : {5.0, 1.5, 0.4}) {
        const BoxGrid grid(boxes, cellMm);
        for (int q = 0; q < 200; ++q) {
            const Box3 query = box(q % 20 == 0);
            std::multiset<std::uint32_t> found;
            grid.overlapping(query, [&](std::uint32_t i) { found.insert(i); });
            std::multiset<std::uint32_t> expected;
            for (std::uint32_t i = 0; i < boxes.size(); ++i)
                if (boxes[i].overlaps(query)) expected.insert(i);
            EXPECT_EQ(found, expected) << cellMm << " mm cells, query " << q;
        }
    }
    // A query far outside, and one that covers everything.
    const BoxGrid grid(boxes, 5.0);
    std::size_t far = 0, all = 0;
    Box3 outside, everything;
    outside.add(Vec3{1000, 1000, 1000});
    everything.add(Vec3{-100, -100, -100});
    everything.add(Vec3{100, 100, 100});
    grid.overlapping(outside, [&](std::uint32_t) { ++far; });
    grid.overlapping(everything, [&](std::uint32_t) { ++all; });
    EXPECT_EQ(far, 0u);
    EXPECT_EQ(all, boxes.size());
    EXPECT_THROW(BoxGrid(boxes, 0), std::invalid_argument);
}

// The order is the grid's promise (cell by cell, z then y then x rising,
// items rising within a cell, each where first met): searches that stop at a
// cap find the same pairs whichever way the cells are stored.
TEST(BoxGrid, VisitsCellByCellInRisingOrder) {
    auto unitBox = [](double x, double y, double z) {
        Box3 b;
        b.add(Vec3{x + 0.1, y + 0.1, z + 0.1});
        b.add(Vec3{x + 0.9, y + 0.9, z + 0.9});
        return b;
    };
    // Listed out of cell order; item 3 spans cells x = 0 and 1 of row y = 1.
    std::vector<Box3> boxes = {unitBox(1, 0, 0), unitBox(0, 1, 0), unitBox(0, 0, 1),
                               unitBox(0, 1, 0), unitBox(0, 0, 0)};
    boxes[3].add(Vec3{1.5, 1.5, 0.5});
    Box3 query;
    query.add(Vec3{0, 0, 0});
    query.add(Vec3{2, 2, 2});
    // Dense; then sparse: one box far away makes the scene 101 cells a side.
    for (const bool farBox : {false, true}) {
        if (farBox) boxes.push_back(unitBox(100, 100, 100));
        const BoxGrid grid(boxes, 1.0);
        std::vector<std::uint32_t> order;
        grid.overlapping(query, [&](std::uint32_t i) { order.push_back(i); });
        EXPECT_EQ(order, (std::vector<std::uint32_t>{4, 0, 1, 3, 2})) << farBox;
    }
}

}  // namespace dfrecon
