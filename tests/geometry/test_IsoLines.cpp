// Marching squares on plain images in pixel-index coordinates: exact
// midpoint crossings for masks, holes clockwise, lattice placement.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "geometry/IsoLines.hpp"

namespace dfrecon {
namespace {

// 0.5 − mask: −½ inside, +½ outside, so crossings are edge midpoints.
std::vector<float> maskImage(int width, int height,
                             const std::vector<std::pair<int, int>>& inside) {
    std::vector<float> values(std::size_t(width * height), 0.5f);
    for (auto [i, j] : inside) values[std::size_t(j * width + i)] = -0.5f;
    return values;
}

bool hasPoint(const Polygon& polygon, Point2 p) {
    return std::find(polygon.begin(), polygon.end(), p) != polygon.end();
}

TEST(IsoLines, SinglePixelIsACounterClockwiseDiamondThroughEdgeMidpoints) {
    const auto polygons = negativeRegionBorders(maskImage(6, 7, {{3, 4}}), 6, 7);
    ASSERT_EQ(polygons.size(), 1u);
    const Polygon& diamond = polygons[0];
    ASSERT_EQ(diamond.size(), 4u);
    for (Point2 p : {Point2{3.5, 4}, Point2{3, 4.5}, Point2{2.5, 4}, Point2{3, 3.5}})
        EXPECT_TRUE(hasPoint(diamond, p)) << p.x << ", " << p.y;
    EXPECT_DOUBLE_EQ(signedArea(diamond), 0.5);
}

TEST(IsoLines, RingGivesOuterAndClockwiseHole) {
    // A 3 × 3 ring in a 5 × 5 image.
    std::vector<std::pair<int, int>> ring;
    for (int j = 1; j < 4; ++j)
        for (int i = 1; i < 4; ++i)
            if (i != 2 || j != 2) ring.push_back({i, j});
    const auto polygons = negativeRegionBorders(maskImage(5, 5, ring), 5, 5);
    ASSERT_EQ(polygons.size(), 2u);
    std::vector<double> areas{signedArea(polygons[0]), signedArea(polygons[1])};
    std::sort(areas.begin(), areas.end());
    EXPECT_DOUBLE_EQ(areas[0], -0.5);           // the hole: a diamond round pixel (2, 2)
    EXPECT_DOUBLE_EQ(areas[1], 9 - 4 * 0.125);  // the square with its corners cut
}

TEST(IsoLines, OutsideTheImageCountsAsPlusOne) {
    // All negative (−½): the border crosses towards the +1 outside at t = 1/3.
    const auto polygons = negativeRegionBorders(std::vector<float>(4, -0.5f), 2, 2);
    ASSERT_EQ(polygons.size(), 1u);
    Box2 box;
    for (Point2 p : polygons[0]) box.add(p);
    EXPECT_NEAR(box.min.x, -1.0 / 3, 1e-12);
    EXPECT_NEAR(box.max.y, 1 + 1.0 / 3, 1e-12);
    EXPECT_GT(signedArea(polygons[0]), 0);
}

TEST(IsoLines, DiagonalNeighboursStaySeparate) {
    const auto polygons = negativeRegionBorders(maskImage(4, 4, {{1, 1}, {2, 2}}), 4, 4);
    ASSERT_EQ(polygons.size(), 2u);
    for (const Polygon& polygon : polygons) EXPECT_DOUBLE_EQ(signedArea(polygon), 0.5);
}

TEST(IsoLines, LatticePlacesSamplesWithAnisotropicStepsAndOffsets) {
    SampleLattice lattice;
    lattice.originMm = {10, -5};
    lattice.stepMm = {0.5, 2};
    lattice.indexOffset = {3, 1};
    const auto polygons = negativeRegionBorders(maskImage(3, 3, {{1, 1}}), 3, 3, lattice);
    ASSERT_EQ(polygons.size(), 1u);
    // Sample (1, 1) sits at (10 + 4·0.5, −5 + 2·2) = (12, −1).
    for (Point2 p : {Point2{12.25, -1}, Point2{11.75, -1}, Point2{12, 0}, Point2{12, -2}})
        EXPECT_TRUE(hasPoint(polygons[0], p)) << p.x << ", " << p.y;
    EXPECT_GT(signedArea(polygons[0]), 0);
}

TEST(IsoLines, BadArgumentsAreRefused) {
    EXPECT_THROW(negativeRegionBorders(std::vector<float>(5, 1.0f), 2, 3), std::invalid_argument);
    SampleLattice flipped;
    flipped.stepMm = {-1, 1};
    EXPECT_THROW(negativeRegionBorders(std::vector<float>(4, 1.0f), 2, 2, flipped),
                 std::invalid_argument);
    EXPECT_TRUE(negativeRegionBorders({}, 0, 0).empty());
}

}  // namespace
}  // namespace dfrecon
