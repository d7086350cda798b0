// Polygon predicates against hand-computed answers.
#include <gtest/gtest.h>

#include "geometry/Polygon.hpp"

using namespace dfrecon;

TEST(Polygon, SignedAreaOfUnitSquareBothWays) {
    Polygon square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    EXPECT_DOUBLE_EQ(signedArea(square), 1.0);
    std::reverse(square.begin(), square.end());
    EXPECT_DOUBLE_EQ(signedArea(square), -1.0);
}

TEST(Polygon, SignedAreaFarFromOriginKeepsPrecision) {
    const double o = 1e6;
    const Polygon square{{o, o}, {o + 1e-3, o}, {o + 1e-3, o + 1e-3}, {o, o + 1e-3}};
    EXPECT_NEAR(signedArea(square), 1e-6, 1e-12);
}

TEST(Polygon, RegionCentroidIsTheCentreOfMass) {
    // An L of three unit squares: the mean of their centres, (5/6, 5/6);
    // either orientation, and far from the origin.
    const Polygon l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    const Point2 c = regionCentroid(l);
    EXPECT_NEAR(c.x, 5.0 / 6.0, 1e-12);
    EXPECT_NEAR(c.y, 5.0 / 6.0, 1e-12);
    Polygon far(l.rbegin(), l.rend());
    for (Point2& p : far) p = p + Point2{1e5, -2e5};
    const Point2 cf = regionCentroid(far);
    EXPECT_NEAR(cf.x, 1e5 + 5.0 / 6.0, 1e-9);
    EXPECT_NEAR(cf.y, -2e5 + 5.0 / 6.0, 1e-9);
    // No area: the mean of the points.
    const Point2 flat = regionCentroid({{0, 0}, {2, 0}, {4, 0}});
    EXPECT_NEAR(flat.x, 2, 1e-12);
    EXPECT_NEAR(flat.y, 0, 1e-12);
}

TEST(Polygon, WindingNumberCountsTurns) {
    const Polygon ccw{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    Polygon cw = ccw;
    std::reverse(cw.begin(), cw.end());
    EXPECT_EQ(windingNumber({2, 2}, ccw), 1);
    EXPECT_EQ(windingNumber({2, 2}, cw), -1);
    EXPECT_EQ(windingNumber({5, 2}, ccw), 0);
    EXPECT_EQ(windingNumber({-1, 2}, ccw), 0);
    // A vertex level with the query point must not be counted twice.
    const Polygon diamond{{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    EXPECT_EQ(windingNumber({0, 0}, diamond), 1);
    EXPECT_EQ(windingNumber({-2, 0}, diamond), 0);
    EXPECT_EQ(windingNumber({2, 0}, diamond), 0);
}

TEST(Polygon, DistanceToSegmentAndBoundary) {
    EXPECT_DOUBLE_EQ(distanceToSegment({0, 1}, {-1, 0}, {1, 0}), 1.0);
    EXPECT_DOUBLE_EQ(distanceToSegment({3, 4}, {0, 0}, {0, 0}), 5.0);
    EXPECT_DOUBLE_EQ(distanceToSegment({4, 4}, {0, 0}, {1, 0}), 5.0);
    const Polygon square{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
    EXPECT_DOUBLE_EQ(distanceToBoundary({1, 2}, square), 1.0);
}

TEST(Polygon, SegmentContactClasses) {
    EXPECT_EQ(segmentContact({0, 0}, {2, 2}, {0, 2}, {2, 0}), SegmentContact::Cross);
    EXPECT_EQ(segmentContact({0, 0}, {1, 0}, {0, 1}, {1, 1}), SegmentContact::None);
    EXPECT_EQ(segmentContact({0, 0}, {1, 0}, {1, 0}, {2, 1}), SegmentContact::Touch);
    EXPECT_EQ(segmentContact({0, 0}, {2, 0}, {1, 0}, {1, 1}), SegmentContact::Touch);  // T
    EXPECT_EQ(segmentContact({0, 0}, {2, 0}, {1, 0}, {3, 0}), SegmentContact::Overlap);
    EXPECT_EQ(segmentContact({0, 0}, {1, 0}, {1, 0}, {2, 0}), SegmentContact::Touch);
    EXPECT_EQ(segmentContact({0, 0}, {1, 0}, {2, 0}, {3, 0}), SegmentContact::None);
    EXPECT_EQ(segmentContact({0, 0}, {0, 2}, {0, 1}, {0, 3}), SegmentContact::Overlap);
}
