// findContourDefect against brute-force all-pairs checks on random polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/ContourValidation.hpp"

using namespace dfrecon;

namespace {

// The all-pairs reference: is there any defect at all?
bool bruteForceHasDefect(const std::vector<Polygon>& contours) {
    for (std::size_t c = 0; c < contours.size(); ++c)
        for (std::size_t d = c; d < contours.size(); ++d)
            for (std::size_t i = 0; i < contours[c].size(); ++i)
                for (std::size_t j = (c == d ? i + 1 : 0); j < contours[d].size(); ++j) {
                    const Polygon &p = contours[c], &q = contours[d];
                    const SegmentContact contact =
                        segmentContact(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()]);
                    if (contact == SegmentContact::None) continue;
                    if (c == d) {
                        const bool adjacent = j == i + 1 || (i == 0 && j == p.size() - 1);
                        if (adjacent && contact != SegmentContact::Overlap) continue;
                        return true;
                    }
                    if (contact != SegmentContact::Touch) return true;
                }
    return false;
}

Polygon randomStarPolygon(std::mt19937& random, Point2 centre, int n, double rMin, double rMax) {
    std::uniform_real_distribution<double> radius(rMin, rMax);
    Polygon p;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * M_PI * k / n;
        const double r = radius(random);
        p.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
    }
    return p;
}

}  // namespace

TEST(ContourValidation, ValidNestedContoursPass) {
    const Polygon outer{{0, 0}, {30, 0}, {30, 30}, {0, 30}};
    const Polygon hole{{5, 5}, {5, 25}, {25, 25}, {25, 5}};
    EXPECT_FALSE(findContourDefect({outer, hole}).has_value());
}

TEST(ContourValidation, ReportsTheCrossingSegments) {
    const Polygon bowtie{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
    const auto defect = findContourDefect({bowtie});
    ASSERT_TRUE(defect.has_value());
    EXPECT_EQ(defect->kind, ContourDefect::Kind::SelfIntersection);
    EXPECT_EQ(defect->segmentA, 0u);
    EXPECT_EQ(defect->segmentB, 2u);
}

TEST(ContourValidation, AgreesWithBruteForceOnRandomStars) {
    std::mt19937 random(7);
    int defects = 0, clean = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::uniform_real_distribution<double> offset(-12, 12);
        std::vector<Polygon> contours = {
            randomStarPolygon(random, {0, 0}, 5 + trial % 40, 2, 10),
            randomStarPolygon(random, {offset(random), offset(random)}, 4 + trial % 17, 1, 6)};
        // Occasionally swap two vertices to make self-intersections likely.
        if (trial % 3 == 0) std::swap(contours[0][1], contours[0][3]);
        const bool expected = bruteForceHasDefect(contours);
        EXPECT_EQ(findContourDefect(contours).has_value(), expected) << "trial " << trial;
        (expected ? defects : clean)++;
    }
    EXPECT_GT(defects, 30);  // both outcomes exercised
    EXPECT_GT(clean, 30);
}

TEST(ContourValidation, PairBudgetTurnsPathologyIntoAnError) {
    std::mt19937 random(1);
    const Polygon star = randomStarPolygon(random, {0, 0}, 2000, 5, 10);
    ASSERT_FALSE(findContourDefect({star}).has_value());
    const auto defect = findContourDefect({star}, 100);
    ASSERT_TRUE(defect.has_value());
    EXPECT_EQ(defect->kind, ContourDefect::Kind::TooComplex);
}

TEST(ContourValidation, LongSegmentsCannotExhaustMemory) {
    // A comb of 20000 hair-thin teeth as tall as the comb is wide: every
    // tooth edge crosses the whole grid. Valid, but refused with an error
    // instead of billions of grid entries.
    Polygon comb{{400, 1}, {400, 0}, {0, 0}};
    for (int i = 0; i < 20000; ++i) {
        const double x = 0.02 * i;
        for (Point2 p : {Point2{x, 1}, Point2{x, 400}, Point2{x + 0.01, 400}, Point2{x + 0.01, 1}})
            comb.push_back(p);
    }
    const auto defect = findContourDefect({comb});
    ASSERT_TRUE(defect.has_value());
    EXPECT_EQ(defect->kind, ContourDefect::Kind::TooComplex);
}

TEST(ContourValidation, ContoursTouchingAtAPointAreValid) {
    const Polygon a = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Polygon cornerToCorner = {{10, 10}, {20, 10}, {20, 20}, {10, 20}};
    const Polygon vertexOnEdge = {{5, 10}, {8, 15}, {2, 15}};  // outside, tip on a's top edge
    const Polygon holeTouching = {{5, 0}, {7, 5}, {3, 5}};     // inside, tip on a's bottom edge
    EXPECT_FALSE(findContourDefect({a, cornerToCorner}));
    EXPECT_FALSE(findContourDefect({a, vertexOnEdge}));
    EXPECT_FALSE(findContourDefect({a, holeTouching}));
}

TEST(ContourValidation, ContoursCrossingOnlyAtSharedPointsAreCrossings) {
    // A square whose corners lie on a triangle's hypotenuse: the boundaries
    // meet only at those points but pass through each other there (a fuzz
    // finding: the nesting then depended on the square's starting point).
    const Polygon triangle = {{0, 0}, {20, 0}, {0, 20}};
    const Polygon square = {{5, 5}, {15, 5}, {15, 15}, {5, 15}};
    const auto defect = findContourDefect({triangle, square});
    ASSERT_TRUE(defect);
    EXPECT_EQ(defect->kind, ContourDefect::Kind::Crossing);
    EXPECT_EQ(defect->contact, SegmentContact::Cross);
    // Corner to corner, but passing through: two squares sharing the corner
    // (10, 10), the second entering the first there.
    const Polygon a = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Polygon through = {{10, 10}, {5, 12}, {-2, 4}};
    EXPECT_TRUE(findContourDefect({a, through}));
}

TEST(ContourValidation, CountsEachMeetingPairOfSegmentsOnce) {
    // Random stars against the all-pairs count, in grids of every coarseness.
    std::mt19937 random(7);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<Polygon> stars;
        for (int s = 0; s < 4; ++s)
            stars.push_back(randomStarPolygon(random, {double(s), 0}, 30, 2, 6));
        std::size_t expected = 0;
        for (std::size_t c = 0; c < stars.size(); ++c)
            for (std::size_t d = c + 1; d < stars.size(); ++d)
                for (std::size_t i = 0; i < stars[c].size(); ++i)
                    for (std::size_t j = 0; j < stars[d].size(); ++j)
                        expected += segmentContact(stars[c][i], stars[c][(i + 1) % 30], stars[d][j],
                                                   stars[d][(j + 1) % 30]) != SegmentContact::None;
        EXPECT_EQ(countContourContacts(stars, 1u << 20), expected);
        // It stops one past the limit.
        if (expected > 3) {
            EXPECT_EQ(countContourContacts(stars, 3), 4u);
        }
    }
}
