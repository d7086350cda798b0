// Keyhole contours: a hole joined to its outer contour by a zero-width
// channel comes apart into the outer loop and the hole, by area.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/KeyholeSplit.hpp"

using namespace dfrecon;

namespace {

std::vector<double> sortedAreas(const std::vector<Polygon>& loops) {
    std::vector<double> areas;
    for (const Polygon& loop : loops) areas.push_back(std::abs(signedArea(loop)));
    std::sort(areas.begin(), areas.end());
    return areas;
}

// A 10×10 square with a 4×4 square hole, joined at x = 5 by a channel down
// from the outer bottom edge (the way plastimatch writes holes).
Polygon squareKeyhole(bool channelSidesShareVertices) {
    Polygon p = {{0, 0}, {5, 0}, {5, 3}};  // along the bottom, up the channel
    for (Point2 q : {Point2{3, 3}, Point2{3, 7}, Point2{7, 7}, Point2{7, 3}, Point2{5, 3}})
        p.push_back(q);  // around the hole, clockwise, back to the channel's top
    if (!channelSidesShareVertices) p.push_back({5, 1.5});  // a point the way up lacks
    for (Point2 q : {Point2{5, 0}, Point2{10, 0}, Point2{10, 10}, Point2{0, 10}}) p.push_back(q);
    return p;
}

}  // namespace

TEST(KeyholeSplit, ChannelSharingVerticesSplitsIntoOuterAndHole) {
    const KeyholeSplit split = splitKeyholes(squareKeyhole(true));
    ASSERT_EQ(split.loops.size(), 2u);
    EXPECT_GT(split.cuts, 0u);
    const std::vector<double> areas = sortedAreas(split.loops);
    EXPECT_DOUBLE_EQ(areas[0], 16.0);
    EXPECT_DOUBLE_EQ(areas[1], 100.0);
}

TEST(KeyholeSplit, ChannelSidesSampledApartStillSplit) {
    const KeyholeSplit split = splitKeyholes(squareKeyhole(false));
    ASSERT_EQ(split.loops.size(), 2u);
    const std::vector<double> areas = sortedAreas(split.loops);
    EXPECT_DOUBLE_EQ(areas[0], 16.0);
    EXPECT_DOUBLE_EQ(areas[1], 100.0);
}

TEST(KeyholeSplit, TwoHolesThroughOneContour) {
    // Outer 0..20 × 0..10, holes 2..6 and 12..16 (× 3..7), channels at x = 4
    // and x = 14 from the bottom edge.
    Polygon p = {{0, 0},  {4, 0},  {4, 3},  {2, 3},  {2, 7},   {6, 7},  {6, 3},
                 {4, 3},  {4, 0},  {14, 0}, {14, 3}, {12, 3},  {12, 7}, {16, 7},
                 {16, 3}, {14, 3}, {14, 0}, {20, 0}, {20, 10}, {0, 10}};
    const KeyholeSplit split = splitKeyholes(p);
    ASSERT_EQ(split.loops.size(), 3u);
    const std::vector<double> areas = sortedAreas(split.loops);
    EXPECT_DOUBLE_EQ(areas[0], 16.0);
    EXPECT_DOUBLE_EQ(areas[1], 16.0);
    EXPECT_DOUBLE_EQ(areas[2], 200.0);
}

TEST(KeyholeSplit, SimplePolygonComesBackUnchanged) {
    const Polygon circle = circlePolygon({1, 2}, 5, 40);
    const KeyholeSplit split = splitKeyholes(circle);
    EXPECT_EQ(split.cuts, 0u);
    ASSERT_EQ(split.loops.size(), 1u);
    EXPECT_EQ(split.loops[0], circle);
}

TEST(KeyholeSplit, FigureEightPinchGivesTwoLoops) {
    // Two triangles meeting at the origin, traced as one path.
    const Polygon p = {{0, 0}, {2, -1}, {2, 1}, {0, 0}, {-2, 1}, {-2, -1}};
    const KeyholeSplit split = splitKeyholes(p);
    ASSERT_EQ(split.loops.size(), 2u);
    const std::vector<double> areas = sortedAreas(split.loops);
    EXPECT_DOUBLE_EQ(areas[0], 2.0);
    EXPECT_DOUBLE_EQ(areas[1], 2.0);
}
