// Contours as planning systems draw them, read by the even-odd rule and
// checked against the rule itself (brute force: a point is inside exactly
// when a ray from it crosses the drawn contours an odd number of times).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "geometry/ContourValidation.hpp"
#include "geometry/PlaneReading.hpp"
#include "geometry/PolygonXor.hpp"

namespace dfrecon {
namespace {

// Parity of the crossings of a ray towards +x with the contours' edges
// (half-open at vertices): the even-odd rule, brute force.
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

// What a Slice may hold: each contour simple, none crossing another.
void expectValidPlane(const std::vector<Polygon>& contours) {
    for (const Polygon& c : contours) EXPECT_FALSE(findContourDefect({c}).has_value());
    const auto defect = findContourDefect(contours);
    EXPECT_TRUE(!defect || defect->contact == SegmentContact::Touch);
}

// Random points away from every edge agree with the rule on the drawing.
int disagreements(const std::vector<Polygon>& drawn, const std::vector<Polygon>& read,
                  std::mt19937& random, double extent) {
    std::uniform_real_distribution<double> coordinate(-extent, extent);
    int disagree = 0;
    for (int s = 0; s < 400; ++s) {
        const Point2 p{coordinate(random), coordinate(random)};
        double nearest = INFINITY;
        for (const Polygon& c : drawn) nearest = std::min(nearest, distanceToBoundary(p, c));
        if (nearest < 1e-6) continue;
        disagree += oddInside(drawn, p) != oddInside(read, p);
    }
    return disagree;
}

TEST(PolygonXor, BowTieBecomesItsTwoTriangles) {
    const Polygon bowTie{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
    const std::vector<Polygon> region = xorRegions({bowTie}, 10'000);
    ASSERT_EQ(region.size(), 2u);
    EXPECT_NEAR(netArea(region), 50.0, 1e-12);
    for (const Polygon& c : region) EXPECT_GT(signedArea(c), 0);  // outer: counter-clockwise
    expectValidPlane(region);
}

TEST(PolygonXor, PathDrawnTwiceBoundsNothing) {
    const Polygon twice{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}, {4, 0}, {4, 4}, {0, 4}};
    EXPECT_TRUE(xorRegions({twice}, 10'000).empty());
}

TEST(PolygonXor, HoleTouchingItsOuterBoundaryComesBackAsTwoLoops) {
    const Polygon outer{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Polygon hole{{0, 5}, {5, 2}, {5, 8}};  // touches the outer at (0, 5)
    const std::vector<Polygon> region = xorRegions({outer, hole}, 10'000);
    ASSERT_EQ(region.size(), 2u);
    EXPECT_NEAR(netArea(region), 100.0 - 15.0, 1e-12);
    expectValidPlane(region);
}

TEST(PolygonXor, KeepsEveryPointOnTheBoundaryExactly) {
    // Two overlapping squares with points that are not short decimals.
    const Polygon a{{0.1, 0.1}, {10.3, 0.1}, {10.3, 10.7}, {0.1, 10.7}};
    const Polygon b{{5.05, 5.05}, {15.15, 5.05}, {15.15, 15.25}, {5.05, 15.25}};
    const std::vector<Polygon> region = xorRegions({a, b}, 10'000);
    for (const Polygon& drawn : {a, b})
        for (Point2 p : drawn) {
            bool found = false;
            for (const Polygon& c : region) found = found || std::count(c.begin(), c.end(), p) > 0;
            EXPECT_TRUE(found) << p.x << " " << p.y;
        }
}

TEST(PolygonXor, RefusesMoreContoursAndCrossingsThanItMayCombine) {
    // Two squares crossing at two points: 2 contours + 2 crossings.
    const Polygon a = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const Polygon b = {{5, 5}, {15, 5}, {15, 15}, {5, 15}};
    std::size_t work = 0;
    EXPECT_FALSE(xorRegions({a, b}, 4, &work).empty());
    EXPECT_EQ(work, 4u);
    EXPECT_THROW(xorRegions({a, b}, 3), TooManyCrossings);
}

// Random closed paths through random points cross, touch and run along
// themselves; what is read is a valid plane that classifies random points
// as the even-odd rule does on the drawing.
TEST(PolygonXor, RandomPathsMatchTheEvenOddRule) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> grid(-6, 6);  // on a lattice: many collinear overlaps
    std::uniform_real_distribution<double> coordinate(-10, 10);
    for (int trial = 0; trial < 80; ++trial) {
        std::vector<Polygon> drawn(1 + trial % 3);
        for (Polygon& path : drawn) {
            const int points = 4 + trial % 11;
            for (int k = 0; k < points; ++k)
                path.push_back(trial % 2 ? Point2{double(grid(random)), double(grid(random))}
                                         : Point2{coordinate(random), coordinate(random)});
            path.erase(std::unique(path.begin(), path.end()), path.end());
        }
        const std::vector<Polygon> region = xorRegions(drawn, 1'000'000);
        expectValidPlane(region);
        EXPECT_EQ(disagreements(drawn, region, random, 11), 0) << "trial " << trial;
    }
}

TEST(PlaneReading, SimplePlaneKeepsItsContoursAsDrawn) {
    const Polygon outer = circlePolygon({0, 0}, 10, 40);
    const Polygon hole = circlePolygon({0, 0}, 4, 20, true);
    const PlaneReading read = readPlaneContours({outer, hole}, 10'000);
    ASSERT_EQ(read.contours.size(), 2u);
    EXPECT_EQ(read.contours[0], outer);
    EXPECT_EQ(read.contours[1], hole);
    EXPECT_EQ(read.sourceOf, (std::vector<std::size_t>{0, 1}));
    EXPECT_FALSE(read.counts.changedShape());
    EXPECT_EQ(read.counts.summary(), "");
}

TEST(PlaneReading, FoldsRepeatsDuplicatesAndLinesAreDropped) {
    // A square with a spike drawn out and back along one line over two
    // points, and a repeated point.
    const Polygon folded{{0, 0},  {10, 0}, {10, 5}, {14, 5},  {17, 5},
                         {14, 5}, {10, 5}, {10, 5}, {10, 10}, {0, 10}};
    const Polygon square{{20, 0}, {30, 0}, {30, 10}, {20, 10}};
    Polygon again = square;  // the same contour, stored twice, the other way round
    std::reverse(again.begin(), again.end());
    std::rotate(again.begin(), again.begin() + 1, again.end());
    const Polygon line{{40, 0}, {41, 1}, {42, 2}};
    const PlaneReading read = readPlaneContours({folded, square, again, line}, 10'000);
    ASSERT_EQ(read.contours.size(), 2u);
    EXPECT_NEAR(netArea(read.contours), 200.0, 1e-12);
    EXPECT_EQ(read.counts.repeatedPoints, 1u);
    EXPECT_GE(read.counts.foldPoints, 2u);
    EXPECT_EQ(read.counts.duplicateContours, 1u);
    EXPECT_EQ(read.counts.zeroAreaContours, 1u);
    EXPECT_EQ(read.counts.resolvedContours, 0u);  // no fill was needed
    EXPECT_TRUE(read.counts.changedShape());
    expectValidPlane(read.contours);
}

TEST(PlaneReading, EveryContourStoredTwiceKeepsItsRegion) {
    // Even-odd alone would cancel each pair: duplicates go first.
    std::vector<Polygon> drawn;
    for (int k = 0; k < 5; ++k) {
        drawn.push_back(circlePolygon({30.0 * k, 0}, 10, 64));
        drawn.push_back(drawn.back());
    }
    const PlaneReading read = readPlaneContours(drawn, 100);
    EXPECT_EQ(read.contours.size(), 5u);
    EXPECT_EQ(read.counts.duplicateContours, 5u);
}

TEST(PlaneReading, CrossingGroupIsFilledAndTheRestKeptExactly) {
    const Polygon bowTie{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
    const Polygon apart = circlePolygon({50, 50}, 5, 30);
    const PlaneReading read = readPlaneContours({bowTie, apart}, 10'000);
    EXPECT_EQ(read.counts.resolvedContours, 1u);
    EXPECT_EQ(read.counts.planesResolved, 1u);
    ASSERT_EQ(read.contours.size(), 3u);
    const auto kept = std::find(read.sourceOf.begin(), read.sourceOf.end(), std::size_t(1));
    ASSERT_NE(kept, read.sourceOf.end());
    EXPECT_EQ(read.contours[std::size_t(kept - read.sourceOf.begin())], apart);
    expectValidPlane(read.contours);
}

TEST(PlaneReading, RandomMessyPlanesAreValidAndFollowTheRule) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> jitter(-3, 3), unit(0, 1);
    for (int trial = 0; trial < 60; ++trial) {
        std::vector<Polygon> drawn;
        for (int c = 0; c < 1 + trial % 4; ++c) {
            Polygon p = circlePolygon({jitter(random) * 3, jitter(random) * 3},
                                      4 + unit(random) * 6, 8 + trial % 20);
            for (Point2& q : p) q = q + Point2{jitter(random), jitter(random)};  // may cross itself
            if (unit(random) < 0.3) {  // a fold: out to a tip and back over the same points
                const std::size_t at = std::size_t(unit(random) * double(p.size()));
                const Point2 base = p[at], tip = base + Point2{jitter(random) * 2, 5};
                p.insert(p.begin() + std::ptrdiff_t(at) + 1, {tip, base});
            }
            if (unit(random) < 0.2) p.insert(p.begin() + 1, p[1]);  // a repeated point
            drawn.push_back(p);
            if (unit(random) < 0.2) drawn.push_back(p);  // stored twice
        }
        const PlaneReading read = readPlaneContours(drawn, 1'000'000);
        expectValidPlane(read.contours);
        // The rule applies to the drawing with its duplicates taken out.
        std::vector<Polygon> once;
        for (const Polygon& p : drawn)
            if (std::find(once.begin(), once.end(), p) == once.end()) once.push_back(p);
        EXPECT_EQ(disagreements(once, read.contours, random, 30), 0) << "trial " << trial;
    }
}

}  // namespace
}  // namespace dfrecon
