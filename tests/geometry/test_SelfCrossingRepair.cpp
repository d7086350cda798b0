// Self-crossing contours resolved by the even-odd rule, checked against the
// rule itself: a point is inside the repaired contours exactly when a ray
// from it crosses the original contour an odd number of times.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/ContourValidation.hpp"
#include "geometry/SelfCrossingRepair.hpp"

namespace dfrecon {
namespace {

// Parity of the crossings of a ray towards +x with the contours' edges
// (half-open rule at vertices): the even-odd rule, brute force.
bool oddInside(const std::vector<Polygon>& contours, Point2 p) {
    bool inside = false;
    for (const Polygon& c : contours)
        for (std::size_t i = 0, n = c.size(); i < n; ++i) {
            const Point2 a = c[i], b = c[(i + 1) % n];
            if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
                inside = !inside;
        }
    return inside;
}

double netArea(const std::vector<Polygon>& contours) {
    double area = 0;
    for (const Polygon& c : contours) area += signedArea(c);
    return area;
}

TEST(SelfCrossingRepair, BowTieBecomesItsTwoTriangles) {
    const Polygon bowTie{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
    ASSERT_TRUE(findContourDefect({bowTie}).has_value());
    const auto region = evenOddRegion(bowTie, 100, 10'000);
    ASSERT_TRUE(region.has_value());
    ASSERT_EQ(region->size(), 2u);
    EXPECT_NEAR(netArea(*region), 50.0, 1e-12);
    for (const Polygon& c : *region) {
        EXPECT_GT(signedArea(c), 0);  // outer: counter-clockwise
        EXPECT_FALSE(findContourDefect({c}).has_value());
    }
}

TEST(SelfCrossingRepair, SimpleContourComesBackCounterClockwise) {
    const Polygon square{{0, 0}, {0, 4}, {4, 4}, {4, 0}};
    const auto region = evenOddRegion(square, 100, 10'000);
    ASSERT_TRUE(region.has_value());
    ASSERT_EQ(region->size(), 1u);
    EXPECT_NEAR(signedArea(region->front()), 16.0, 1e-12);
}

// A square traced twice runs along itself: cutting cannot separate it, so
// it is no repair (and stays an error for the reader).
TEST(SelfCrossingRepair, PathTracedTwiceIsNotRepaired) {
    const Polygon twice{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}, {4, 0}, {4, 4}, {0, 4}};
    EXPECT_FALSE(evenOddRegion(twice, 100, 10'000).has_value());
}

// Random closed paths through random points cross themselves many times;
// the repaired contours are simple, pairwise non-crossing, and classify
// random points exactly as the even-odd rule does on the original.
TEST(SelfCrossingRepair, RandomPathsMatchTheEvenOddRuleAtRandomPoints) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-10, 10);
    int repaired = 0;
    for (int trial = 0; trial < 40; ++trial) {
        Polygon path;
        const int points = 5 + trial % 12;
        for (int k = 0; k < points; ++k) path.push_back({coordinate(random), coordinate(random)});
        const auto region = evenOddRegion(path, 1000, 100'000);
        if (!region) continue;  // touches or overlaps itself: not repairable, not wrong
        ++repaired;
        for (const Polygon& c : *region) EXPECT_FALSE(findContourDefect({c}).has_value());
        const auto defect = findContourDefect(*region);
        EXPECT_TRUE(!defect || defect->contact != SegmentContact::Cross) << "trial " << trial;
        int disagree = 0;
        for (int s = 0; s < 500; ++s) {
            const Point2 p{coordinate(random), coordinate(random)};
            disagree += oddInside({path}, p) != oddInside(*region, p);
        }
        EXPECT_EQ(disagree, 0) << "trial " << trial;
    }
    EXPECT_GT(repaired, 30);
}

}  // namespace
}  // namespace dfrecon
