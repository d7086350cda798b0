// Nesting depth, orientation normalisation, extent and spacing.
#include <gtest/gtest.h>

#include "contours/ContourSet.hpp"

using namespace dfrecon;

namespace {
Polygon square(double x0, double y0, double size, bool ccw) {
    Polygon p{{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
    if (!ccw) std::reverse(p.begin(), p.end());
    return p;
}
}  // namespace

TEST(ContourSet, NestingDepthsOfIslandInHoleAndNeighbour) {
    Slice slice;
    slice.contours = {square(10, 10, 10, true), square(0, 0, 30, true), square(5, 5, 20, true),
                      square(50, 0, 5, true)};
    EXPECT_EQ(nestingDepths(slice), (std::vector<int>{2, 0, 1, 0}));
}

TEST(ContourSet, TouchingHoleStillCountsAsNested) {
    // The hole shares the outer contour's corner.
    Slice slice;
    slice.contours = {square(0, 0, 10, true), {{0, 0}, {5, 2}, {2, 5}}};
    EXPECT_EQ(nestingDepths(slice), (std::vector<int>{0, 1}));
}

TEST(ContourSet, NormaliseOrientationReversesOnlyWrongOnes) {
    Slice slice;
    slice.contours = {square(0, 0, 30, false), square(5, 5, 20, false), square(10, 10, 10, true),
                      square(50, 0, 5, true)};
    EXPECT_EQ(normaliseOrientation(slice), 1u);
    EXPECT_GT(signedArea(slice.contours[0]), 0);
    EXPECT_LT(signedArea(slice.contours[1]), 0);
    EXPECT_GT(signedArea(slice.contours[2]), 0);
    EXPECT_GT(signedArea(slice.contours[3]), 0);
    EXPECT_EQ(normaliseOrientation(slice), 0u);
}

TEST(ContourSet, ExtentAndSpacing) {
    Roi roi;
    roi.slices = {
        {0, {square(0, 0, 1, true)}}, {2, {square(-1, 0, 1, true)}}, {5, {square(0, 3, 1, true)}}};
    const Extent3 e = extentOf(roi);
    EXPECT_EQ(e.min[0], -1);
    EXPECT_EQ(e.max[1], 4);
    EXPECT_EQ(e.max[2], 5);
    const SpacingStats s = spacingOf(roi);
    EXPECT_EQ(s.minMm, 2);
    EXPECT_EQ(s.maxMm, 3);
    EXPECT_DOUBLE_EQ(s.meanMm, 2.5);
    EXPECT_FALSE(s.uniform);
}
