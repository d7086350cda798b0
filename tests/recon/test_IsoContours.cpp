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
