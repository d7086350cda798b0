// Marching-squares isolines against shapes with known borders.
#include <gtest/gtest.h>

#include <cmath>

#include "recon/IsoContours.hpp"

namespace dfrecon {
namespace {

SliceGrid unitGrid(int size) {
    SliceGrid grid;
    grid.originMm = {-double(size) / 2, -double(size) / 2};
    grid.pixelMm = 1;
    grid.width = grid.height = size;
    return grid;
}

template <class F>
std::vector<float> sample(const SliceGrid& grid, F f) {
    std::vector<float> values;
    for (int j = 0; j < grid.height; ++j)
        for (int i = 0; i < grid.width; ++i) values.push_back(float(f(grid.pixelCentre(i, j))));
    return values;
}

TEST(IsoContours, CircleIsTracedCounterClockwiseOnTheCircle) {
    const SliceGrid grid = unitGrid(40);
    const auto polygons =
        zeroIsolines(sample(grid, [](Point2 p) { return length(p) - 10.3; }), grid);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_GT(signedArea(polygons[0]), 0);
    // Linear interpolation of an exact distance is exact along grid lines
    // up to the curvature: well within a tenth of a pixel at radius 10.
    for (Point2 p : polygons[0]) EXPECT_NEAR(length(p), 10.3, 0.06);
    EXPECT_NEAR(signedArea(polygons[0]), M_PI * 10.3 * 10.3, 2.0);
}

TEST(IsoContours, AnnulusGivesOuterAndClockwiseHole) {
    const SliceGrid grid = unitGrid(40);
    const auto polygons =
        zeroIsolines(sample(grid, [](Point2 p) { return std::abs(length(p) - 10.0) - 4.0; }), grid);
    ASSERT_EQ(polygons.size(), 2u);
    int outer = 0, holes = 0;
    for (const Polygon& polygon : polygons) (signedArea(polygon) > 0 ? outer : holes)++;
    EXPECT_EQ(outer, 1);
    EXPECT_EQ(holes, 1);
}

TEST(IsoContours, RaisedLevelEnclosesTheTargetArea) {
    // The summed field of a disk of radius 3 and one of radius 9 (concentric):
    // its zero set is the circle of radius 6 (area 113 mm²); raised to the
    // mean of the two disks' areas (141 mm², radius 6.7) the isolines are
    // the circle of that area, within the 1 % the search stops at.
    const SliceGrid grid = unitGrid(40);
    const std::vector<float> sum =
        sample(grid, [](Point2 p) { return (length(p) - 3.0) + (length(p) - 9.0); });
    const double mean = 0.5 * (M_PI * 9 + M_PI * 81);
    const auto raised = isolinesEnclosing(sum, grid, {mean, 10.0});
    ASSERT_EQ(raised.size(), 1u);
    EXPECT_NEAR(netArea(raised), mean, 0.02 * mean);
    EXPECT_LE(netArea(raised), mean);
    // Already enough, nothing to enclose, or a level capped: as documented.
    EXPECT_NEAR(netArea(isolinesEnclosing(sum, grid, {50.0, 10.0})),
                netArea(zeroIsolines(sum, grid)), 1e-9);
    const std::vector<float> positive(grid.pixelCount(), 1.0f);
    EXPECT_TRUE(isolinesEnclosing(positive, grid, {100.0, 10.0}).empty());
    const auto capped = isolinesEnclosing(sum, grid, {mean, 0.5});  // circle of radius 6.25
    EXPECT_NEAR(netArea(capped), M_PI * 6.25 * 6.25, 1.5);
    // Bounded by a disk of radius 6.5 (the union of two sides' regions):
    // the raised region stops at it, below the target.
    const std::vector<float> bound = sample(grid, [](Point2 p) { return length(p) - 6.5; });
    const auto bounded = isolinesEnclosing(sum, grid, {mean, 10.0, &bound});
    EXPECT_NEAR(netArea(bounded), M_PI * 6.5 * 6.5, 2.0);
    for (const Polygon& polygon : bounded)
        for (Point2 p : polygon) EXPECT_LE(length(p), 6.5 + 0.06);
}

TEST(IsoContours, NegativeAtTheGridEdgeStillCloses) {
    const SliceGrid grid = unitGrid(10);
    const auto polygons = zeroIsolines(std::vector<float>(100, -1.0f), grid);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_GT(signedArea(polygons[0]), 0);
}

TEST(IsoContours, SaddlesGiveSimpleSeparateLoops) {
    // A checkerboard of single negative pixels: joined corners would form
    // one self-touching loop; the cell means are positive, so each pixel
    // gets its own diamond.
    const SliceGrid grid = unitGrid(8);
    std::vector<float> values(64, 1.0f);
    for (int j = 2; j < 6; ++j)
        for (int i = 2; i < 6; ++i)
            if ((i + j) % 2 == 0) values[std::size_t(j * 8 + i)] = -0.5f;
    const auto polygons = zeroIsolines(values, grid);
    EXPECT_EQ(polygons.size(), 8u);
    for (const Polygon& polygon : polygons) {
        EXPECT_EQ(polygon.size(), 4u);
        EXPECT_GT(signedArea(polygon), 0);
    }
}

}  // namespace
}  // namespace dfrecon
