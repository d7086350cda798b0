// Contour simplification: the bound (every original point within epsilon),
// the recorded per-edge deviations (against brute force), and validity of
// the result (no self-intersections, no crossings), on 1 000 random contours.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "contours/ContourSet.hpp"
#include "geometry/ContourValidation.hpp"
#include "recon/ContourSimplification.hpp"

using namespace dfrecon;

namespace {

// A noisy star polygon: radius varies smoothly plus jitter, so it has both
// long smooth runs (simplify well) and small wiggles.
// A noisy star polygon (smooth lobes plus per-vertex jitter, so it has long
// smooth runs and small wiggles) and, `gapMm` inside it along every ray, a
// hole with the same wiggles: valid, but closer than 2·epsilon.
std::vector<Polygon> starWithHole(std::mt19937& random, Point2 centre, int n, double radius,
                                  double gapMm) {
    std::uniform_real_distribution<double> u(-1, 1);
    const double phase = u(random) * 3, lobes = 2 + int(random() % 5);
    Polygon outer, hole;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * M_PI * k / n;
        const double r = radius * (1 + 0.25 * std::sin(lobes * t + phase)) + 0.8 * u(random);
        outer.push_back({centre.x + r * std::cos(t), centre.y + r * std::sin(t)});
        hole.push_back(
            {centre.x + (r - gapMm) * std::cos(t), centre.y + (r - gapMm) * std::sin(t)});
    }
    return {outer, hole};
}

void expectBoundAndDeviations(const Polygon& original, const SimplifiedContour& s, double epsilon) {
    ASSERT_GE(s.points.size(), 3u);
    ASSERT_EQ(s.points.size(), s.originalIndex.size());
    ASSERT_EQ(s.points.size(), s.edgeDeviationMm.size());
    for (Point2 p : original) EXPECT_LE(distanceToBoundary(p, s.points), epsilon + 1e-12);
    const std::size_t m = s.points.size(), n = original.size();
    for (std::size_t k = 0; k < m; ++k) {
        EXPECT_EQ(s.points[k], original[s.originalIndex[k]]);
        double worst = 0;  // brute force over the replaced chain
        for (std::size_t i = s.originalIndex[k]; i != s.originalIndex[(k + 1) % m]; i = (i + 1) % n)
            worst =
                std::max(worst, distanceToSegment(original[i], s.points[k], s.points[(k + 1) % m]));
        EXPECT_NEAR(s.edgeDeviationMm[k], worst, 1e-12);
        EXPECT_LE(s.edgeDeviationMm[k], epsilon + 1e-12);
    }
}

}  // namespace

TEST(ContourSimplification, BoundDeviationsAndValidityOnRandomContours) {
    std::mt19937 random(2024);
    std::uniform_real_distribution<double> epsilonMm(0.01, 3.0);
    std::size_t pointsIn = 0, pointsOut = 0;
    int tested = 0, refined = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        // An outer contour, a hole close to it, and a neighbour that almost touches.
        const int n = 20 + int(random() % 400);
        Slice slice;
        slice.contours = starWithHole(random, {0, 0}, n, 30, 0.5 + 3 * (random() % 1000) / 1000.0);
        const std::vector<Polygon> neighbour = starWithHole(random, {50, 0}, n / 3 + 3, 9, 1);
        slice.contours.push_back(neighbour[0]);           // an island that nearly touches the first
        if (findContourDefect(slice.contours)) continue;  // rare: the random shape is invalid
        ++tested;
        normaliseOrientation(slice);
        const double epsilon = epsilonMm(random);
        const std::vector<SimplifiedContour> simplified = simplifySlice(slice.contours, epsilon);
        for (std::size_t c = 0; c < simplified.size(); ++c)
            refined += simplified[c].points.size() !=
                       simplifyContour(slice.contours[c], epsilon).points.size();
        ASSERT_EQ(simplified.size(), slice.contours.size());
        std::vector<Polygon> result;
        for (std::size_t c = 0; c < simplified.size(); ++c) {
            expectBoundAndDeviations(slice.contours[c], simplified[c], epsilon);
            result.push_back(simplified[c].points);
            pointsIn += slice.contours[c].size();
            pointsOut += simplified[c].points.size();
        }
        EXPECT_FALSE(findContourDefect(result).has_value()) << "trial " << trial;
        // Orientation survives: kept vertices are in original order.
        for (std::size_t c = 0; c < result.size(); ++c)
            EXPECT_EQ(signedArea(result[c]) > 0, signedArea(slice.contours[c]) > 0);
        if (HasFailure()) break;
    }
    EXPECT_GT(tested, 900);
    EXPECT_GT(refined, 10);              // the crossing repair was exercised
    EXPECT_LT(pointsOut * 3, pointsIn);  // it does simplify
    std::cout << tested << " slices, " << refined << " contours refined against crossings, "
              << pointsIn << " -> " << pointsOut << " points\n";
}

TEST(ContourSimplification, RefinesEdgesThatWouldCrossAnotherContour) {
    // A square with a deep, narrow notch, and a small square inside the
    // notch's mouth: simplifying the notch away would cross it.
    const Polygon notched{{0, 0},   {10, 0},   {10, 4.9}, {5, 4.9},
                          {5, 5.1}, {10, 5.1}, {10, 10},  {0, 10}};
    const Polygon inside{{8, 4.95}, {9, 4.95}, {9, 5.05}, {8, 5.05}};
    ASSERT_FALSE(findContourDefect({notched, inside}).has_value());
    // Alone, the notch (0.1 mm wide) would vanish at epsilon 6.
    EXPECT_LT(simplifyContour(notched, 6).points.size(), notched.size());
    const auto both = simplifySlice({notched, inside}, 6);
    EXPECT_FALSE(findContourDefect({both[0].points, both[1].points}).has_value());
    expectBoundAndDeviations(notched, both[0], 6);
}

TEST(ContourSimplification, KeepsAtLeastATriangle) {
    const Polygon sliver{{0, 0}, {5, 0.01}, {10, 0}, {5, -0.01}};
    const SimplifiedContour s = simplifyContour(sliver, 1);
    EXPECT_EQ(s.points.size(), 3u);
    EXPECT_GT(std::abs(signedArea(s.points)), 0);
}

TEST(ContourSimplification, ZeroEpsilonIsTheIdentity) {
    const Polygon p{{0, 0}, {1, 0}, {2, 0.5}, {1, 1}, {0, 1}};
    const SimplifiedContour s = simplifyContour(p, 0);
    EXPECT_EQ(s.points, p);
    for (double d : s.edgeDeviationMm) EXPECT_EQ(d, 0);
}
