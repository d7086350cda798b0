// The verifier against distances known exactly: a cube and a shifted copy.
#include <gtest/gtest.h>

#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon {
namespace {

TriangleSoup cube(double x0) {
    TriangleSoup s;
    for (int k = 0; k < 8; ++k)
        s.points.push_back({x0 + (k & 1), double((k >> 1) & 1), double(k >> 2)});
    // Outward triangles of the unit cube's six faces.
    s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return s;
}

TEST(SimplificationVerifier, IdenticalSurfacesAreZeroApart) {
    const TwoSidedDistance d = twoSidedDistance(cube(0), cube(0), 2000);
    EXPECT_NEAR(d.maxMm(), 0.0, 1e-12);
    // Cells within the budget and not far below it, and every vertex too.
    EXPECT_LE(d.aToB.samples, 2000u + 8u);
    EXPECT_GT(d.aToB.samples, 1000u + 8u);
    EXPECT_GT(d.spacingMm, 0.0);
    EXPECT_LT(d.spacingMm, 0.1);
}

TEST(SimplificationVerifier, ShiftedCubeIsTheShiftApartBothWays) {
    // Shifted by 0.1 along x: the end faces are 0.1 apart, everything else
    // closer; the corners reach exactly 0.1.
    const TwoSidedDistance d = twoSidedDistance(cube(0), cube(0.1), 5000);
    EXPECT_NEAR(d.aToB.maxMm, 0.1, 1e-12);
    EXPECT_NEAR(d.bToA.maxMm, 0.1, 1e-12);
    EXPECT_GT(d.aToB.meanMm, 0.0);
    EXPECT_LT(d.aToB.meanMm, 0.1);
}

TEST(SimplificationVerifier, ContourSamplesFollowEdgesAndLieOnTheCube) {
    Roi roi;
    roi.slices.push_back({0.5, {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}});
    const std::vector<Vec3> points = contourSamples(roi, 0.1);
    EXPECT_EQ(points.size(), 40u);
    EXPECT_NEAR(distanceToSurface(points, cube(0)).maxMm, 0.0, 1e-12);
    EXPECT_NEAR(distanceToSurface(points, cube(0.25)).maxMm, 0.25, 1e-12);
}

}  // namespace
}  // namespace dfrecon
