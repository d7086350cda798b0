// The per-plane comparison against exact answers (shifted squares, a ring
// against a disc) and the added path length against a brute-force
// reference: dense samples of the test contours, each asked its distance to
// every reference edge.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "compare/PlaneComparison.hpp"
#include "geometry/ClosestPoint.hpp"

using namespace dfrecon;

namespace {

Polygon square(double x0, double y0, double side) {
    return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

Polygon circle(Point2 centre, double radius, int n, bool clockwise = false) {
    Polygon p;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * M_PI * i / n * (clockwise ? -1 : 1);
        p.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)});
    }
    return p;
}

Roi stack(const std::vector<Polygon>& contours, std::vector<double> planes) {
    Roi roi;
    for (double z : planes) roi.slices.push_back({z, contours});
    return roi;
}

double segmentDistance(Point2 p, Point2 a, Point2 b) {
    const Point2 ab = b - a;
    const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
    return length(p - (a + t * ab));
}

// The length of `test` farther than τ from `reference`, by midpoint samples
// `step` apart: within step of the exact length per crossing of the band.
double bruteForceOutside(const std::vector<Polygon>& test, const std::vector<Polygon>& reference,
                         double tau, double step) {
    double outside = 0;
    for (const Polygon& c : test)
        for (std::size_t i = 0; i < c.size(); ++i) {
            const Point2 p = c[i], q = c[(i + 1) % c.size()];
            const double edge = length(q - p);
            const int n = std::max(1, int(std::ceil(edge / step)));
            for (int k = 0; k < n; ++k) {
                const Point2 s = p + ((k + 0.5) / n) * (q - p);
                double d = INFINITY;
                for (const Polygon& r : reference)
                    for (std::size_t j = 0; j < r.size(); ++j)
                        d = std::min(d, segmentDistance(s, r[j], r[(j + 1) % r.size()]));
                if (d > tau) outside += edge / n;
            }
        }
    return outside;
}

}  // namespace

TEST(PlaneComparison, ShiftedSquaresHaveExactOverlapAndAddedPath) {
    // A = [0,10]², B = [3,13]×[0,10] on five planes 2 mm apart. Per plane
    // |A ∩ B| = 70; B's right edge (10) is 3 from A, its top and bottom
    // leave A's band past x = 11 (2 each), its left edge at x = 3 is within
    // 1 of A only for y ≤ 1 or y ≥ 9 (8 outside): 22 a plane.
    const Roi a = stack({square(0, 0, 10)}, {0, 2, 4, 6, 8});
    const Roi b = stack({square(3, 0, 10)}, {0, 2, 4, 6, 8});
    const PlaneComparison c = comparePlanes(a, b, {});
    ASSERT_TRUE(c.samePlanes) << c.whyNot;
    EXPECT_EQ(c.planes, 5u);
    EXPECT_NEAR(c.volumeAMm3, 1000, 1e-9);
    EXPECT_NEAR(c.volumeBMm3, 1000, 1e-9);
    EXPECT_NEAR(c.intersectionMm3, 700, 1e-9);
    EXPECT_NEAR(c.dice(), 0.7, 1e-12);
    EXPECT_NEAR(c.jaccard(), 70.0 / 130, 1e-12);
    EXPECT_NEAR(c.addedPathLengthMm, 5 * 22, 1e-9);
    EXPECT_NEAR(c.addedPathLengthAMm, 5 * 22, 1e-9);  // symmetric by mirror
    EXPECT_NEAR(c.pathLengthBMm, 5 * 40, 1e-9);
}

TEST(PlaneComparison, PlanesOneLacksCountAsEmpty) {
    // B ends a plane sooner and skips one: those planes add to A alone, and
    // all of A's contour there is added path for A.
    const Roi a = stack({square(0, 0, 10)}, {0, 2, 4, 6, 8});
    const Roi b = stack({square(0, 0, 10)}, {0, 4, 6});
    const PlaneComparison c = comparePlanes(a, b, {});
    ASSERT_TRUE(c.samePlanes) << c.whyNot;
    EXPECT_NEAR(c.volumeAMm3, 1000, 1e-9);
    EXPECT_NEAR(c.volumeBMm3, 600, 1e-9);
    EXPECT_NEAR(c.intersectionMm3, 600, 1e-9);
    EXPECT_NEAR(c.addedPathLengthMm, 0, 1e-9);
    EXPECT_NEAR(c.addedPathLengthAMm, 2 * 40, 1e-9);
}

TEST(PlaneComparison, PlanesLeftEmptyInBothEndTheRunAsTheContourVolumeDoes) {
    // Planes 0-2 and 8-9 (1 mm apart, planes 3-7 left empty): each run
    // weighs its planes on its own, so the per-plane volumes are the
    // contour volumes, not 4 mm planes either side of the gap.
    Roi a = stack({square(0, 0, 10)}, {0, 1, 2, 8, 9});
    a.restartsAt = {3};
    Roi b = stack({square(5, 0, 10)}, {0, 1, 2, 8, 9});
    b.restartsAt = {3};
    const PlaneComparison c = comparePlanes(a, b, {});
    ASSERT_TRUE(c.samePlanes) << c.whyNot;
    EXPECT_NEAR(c.volumeAMm3, contourVolumeMm3(a), 1e-9);
    EXPECT_NEAR(c.volumeAMm3, 100.0 * 5, 1e-9);  // 3 + 2 planes of 1 mm
    EXPECT_NEAR(c.volumeBMm3, contourVolumeMm3(b), 1e-9);
    EXPECT_NEAR(c.intersectionMm3, 50.0 * 5, 1e-9);
    // Where B goes on across the gap, the planes of both run on there: the
    // planes next to it stand for half of it each, for A as for B.
    const Roi full = stack({square(5, 0, 10)}, {0, 1, 2, 8, 9});
    const PlaneComparison across = comparePlanes(a, full, {});
    EXPECT_NEAR(across.volumeAMm3, 100.0 * (1 + 1 + 3.5 + 3.5 + 1), 1e-9);
}

TEST(PlaneComparison, HolesAndIdenticalContours) {
    // A ring (r 10 with a hole of r 5) against the full disc of r 10: the
    // intersection is the ring; the hole's contour is all added path for A
    // (5 from the disc's edge, beyond any tolerance under 5).
    const Polygon outer = circle({0, 0}, 10, 64), hole = circle({0, 0}, 5, 64, true);
    const Roi ring = stack({outer, hole}, {0, 3, 6});
    const Roi disc = stack({outer}, {0, 3, 6});
    const PlaneComparison c = comparePlanes(ring, disc, {2.0});
    ASSERT_TRUE(c.samePlanes);
    const double ringArea = signedArea(outer) + signedArea(hole);
    EXPECT_NEAR(c.volumeAMm3, 9 * ringArea, 1e-9);
    EXPECT_NEAR(c.intersectionMm3, 9 * ringArea, 1e-7);
    EXPECT_NEAR(c.addedPathLengthMm, 0, 1e-9);
    double holeLength = 0;
    for (std::size_t i = 0; i < hole.size(); ++i)
        holeLength += length(hole[(i + 1) % hole.size()] - hole[i]);
    EXPECT_NEAR(c.addedPathLengthAMm, 3 * holeLength, 1e-9);
    const PlaneComparison same = comparePlanes(ring, ring, {});
    EXPECT_NEAR(same.dice(), 1, 1e-12);
    EXPECT_NEAR(same.addedPathLengthMm, 0, 1e-12);
}

TEST(PlaneComparison, InterleavedOrNonParallelPlanesAreNotCompared) {
    const Roi a = stack({square(0, 0, 10)}, {0, 2, 4});
    EXPECT_FALSE(comparePlanes(a, stack({square(0, 0, 10)}, {1, 3}), {}).samePlanes);
    EXPECT_FALSE(comparePlanes(a, stack({square(0, 0, 10)}, {0, 3, 6}), {}).samePlanes);
    Roi sagittal = stack({square(0, 0, 10)}, {0, 2, 4});
    sagittal.frame = PlaneFrame{{0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    const PlaneComparison c = comparePlanes(a, sagittal, {});
    EXPECT_FALSE(c.samePlanes);
    EXPECT_FALSE(c.whyNot.empty());
    // Planes a rounding apart are one plane.
    EXPECT_TRUE(comparePlanes(a, stack({square(0, 0, 10)}, {0.0004, 2.0004, 4}), {}).samePlanes);
}

TEST(PlaneComparison, AddedPathLengthMatchesBruteForceOnRandomContours) {
    // Wobbly circles, one perturbed against the other at several tolerances:
    // the exact length against dense samples (5 µm apart: the sampled length
    // is within 5 µm per band crossing, a few hundred crossings at most).
    std::mt19937 random(7);
    std::uniform_real_distribution<double> wobble(-1.5, 1.5);
    for (int trial = 0; trial < 4; ++trial) {
        Polygon reference, test;
        for (int i = 0; i < 90; ++i) {
            const double angle = 2 * M_PI * i / 90;
            const double r = 20 + wobble(random), s = 20 + wobble(random);
            reference.push_back({r * std::cos(angle), r * std::sin(angle)});
            test.push_back({s * std::cos(angle + 0.01) + 0.3, s * std::sin(angle + 0.01)});
        }
        for (double tau : {0.0, 0.5, 1.0, 2.0}) {
            const double exact = lengthOutsideTolerance({test}, {reference}, tau);
            const double sampled = bruteForceOutside({test}, {reference}, tau, 0.005);
            EXPECT_NEAR(exact, sampled, 0.005 * 2 * 90) << trial << " " << tau;
            if (tau > 0) {
                EXPECT_GT(exact, 0);
            }
        }
    }
}
