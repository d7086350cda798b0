// Planar regions by constrained triangulation, checked by exact areas.
#include <gtest/gtest.h>

#include "recon/PlanarRegion.hpp"

namespace dfrecon {
namespace {

Polygon square(double x0, double y0, double side, bool clockwise = false) {
    Polygon p{{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
    if (clockwise) std::reverse(p.begin(), p.end());
    return p;
}

// Total signed area of the kept triangles, each counted with its sign.
double weightedArea(const PlanarRegion& region) {
    double sum = 0;
    for (std::size_t t = 0; t < region.triangles.size(); ++t) {
        const auto& tri = region.triangles[t];
        const Polygon p{region.points[tri[0]], region.points[tri[1]], region.points[tri[2]]};
        EXPECT_GT(signedArea(p), 0) << "triangles are counter-clockwise";
        sum += region.sign[t] * signedArea(p);
    }
    return sum;
}

TEST(PlanarRegion, SquareWithHoleKeepsTheRing) {
    const Polygon outer = square(0, 0, 10), hole = square(3, 3, 4, true);
    const PlanarRegion region = triangulateRegion({{&outer, 1}, {&hole, 1}});
    EXPECT_NEAR(weightedArea(region), 100 - 16, 1e-9);
    ASSERT_EQ(region.edgeChains.size(), 2u);
    for (const auto& chains : region.edgeChains)
        for (const auto& chain : chains) EXPECT_EQ(chain.size(), 2u) << "nothing crosses";
}

// Two equal points in a row (an intermediate contour once rounded) make an
// edge of no length: its chain is its one point, and the region is the
// contour's (CGAL gave the edge a null constraint, which crashed).
TEST(PlanarRegion, AnEdgeOfNoLengthIsItsOnePoint) {
    const Polygon repeated{{0, 0}, {10, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Polygon other = square(2, 2, 3);  // counted against: a hole in the region
    const PlanarRegion region = triangulateRegion({{&repeated, 1}, {&other, -1}});
    EXPECT_NEAR(weightedArea(region), 100 - 9, 1e-9);
    ASSERT_EQ(region.edgeChains[0].size(), 5u);
    EXPECT_EQ(region.edgeChains[0][1].size(), 1u);
    EXPECT_EQ(region.edgeChains[0][0].back(), region.edgeChains[0][1].front());
}

TEST(PlanarRegion, CrossingContoursGiveTheSymmetricDifferenceWithSigns) {
    // X (weight +1) and Y (weight -1) overlap in a 5 x 5 square.
    const Polygon x = square(0, 0, 10), y = square(5, 5, 10);
    const PlanarRegion region = triangulateRegion({{&x, 1}, {&y, -1}});
    double positive = 0, negative = 0;
    for (std::size_t t = 0; t < region.triangles.size(); ++t) {
        const auto& tri = region.triangles[t];
        const double a = signedArea(
            Polygon{region.points[tri[0]], region.points[tri[1]], region.points[tri[2]]});
        (region.sign[t] > 0 ? positive : negative) += a;
    }
    EXPECT_NEAR(positive, 75, 1e-9);
    EXPECT_NEAR(negative, 75, 1e-9);
    // X's edges 1 (right) and 2 (top) are each crossed once by Y.
    EXPECT_EQ(region.edgeChains[0][0].size(), 2u);
    EXPECT_EQ(region.edgeChains[0][1].size(), 3u);
    EXPECT_EQ(region.edgeChains[0][2].size(), 3u);
    const Point2 crossing = region.points[region.edgeChains[0][1][1]];
    EXPECT_DOUBLE_EQ(crossing.x, 10);
    EXPECT_DOUBLE_EQ(crossing.y, 5);
}

TEST(PlanarRegion, SteinerPointsBecomeInnerVertices) {
    const Polygon outer = square(0, 0, 10);
    const PlanarRegion region = triangulateRegion({{&outer, 1}}, {{5, 5}, {2, 7}});
    EXPECT_EQ(region.points.size(), 6u);
    EXPECT_EQ(region.triangles.size(), 6u);  // 2·inner + corners - 2
    EXPECT_NEAR(weightedArea(region), 100, 1e-9);
}

}  // namespace
}  // namespace dfrecon
