// Overlap and surface distances between two structures against exact
// formulas: boxes (whose overlap is a box), nested boxes (every point of the
// inner surface exactly d from the outer), offset spheres (the lens formula).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <utility>

#include "cl/Runtime.hpp"
#include "compare/OverlapVolume.hpp"
#include "field/SurfaceDistances.hpp"
#include "geometry/ClosestPoint.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleCells.hpp"
#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(OverlapVolume, OffsetBoxesOverlapInABox) {
    for (double d : {0.0, 0.5, 3.25, 9.0}) {
        const TriangleSoup a = boxMesh({0, 0, 0}, {10, 10, 10}, 3);
        const TriangleSoup b = boxMesh({d, 0, 0}, {10 + d, 10, 10}, 4);
        const Overlap o = overlapOf(a, b);
        EXPECT_NEAR(o.volumeAMm3, 1000, 1e-9);
        EXPECT_NEAR(o.volumeBMm3, 1000, 1e-9);
        // The faces share planes: B is moved by 1e-9 mm, which the bound
        // states (area(B) · shift and the flux's rounding).
        EXPECT_LE(o.intersectionBoundMm3, 600 * 1e-9 + 1e-9) << d;
        EXPECT_NEAR(o.intersectionMm3, 100 * (10 - d), o.intersectionBoundMm3) << d;
        EXPECT_NEAR(o.dice(), (10 - d) / 10, o.intersectionBoundMm3 / 1000) << d;
        EXPECT_NEAR(o.jaccard(), (10 - d) / (10 + d), 2e-3 * o.intersectionBoundMm3) << d;
    }
}

TEST(OverlapVolume, DisjointAndNestedSolids) {
    const TriangleSoup a = boxMesh({0, 0, 0}, {10, 10, 10}, 2);
    EXPECT_NEAR(overlapOf(a, boxMesh({20, 0, 0}, {30, 10, 10}, 2)).dice(), 0, 1e-12);
    const Overlap nested = overlapOf(a, boxMesh({2, 2, 2}, {4, 4, 4}, 2));
    EXPECT_NEAR(nested.intersectionMm3, 8, 1e-9);
    EXPECT_NEAR(nested.dice(), 16.0 / 1008, 1e-12);
}

TEST(OverlapVolume, OffsetSpheresFollowTheLensFormula) {
    // Fine geodesic spheres: the polyhedra's volumes approach the balls'; the
    // Dice of the polyhedra approaches (4R + d)(2R − d)² / (16 R³).
    const double r = 10;
    for (double d : {2.0, 8.0}) {
        const TriangleSoup a = geodesicSphere(48, r), b = geodesicSphere(48, r, {d, 0, 0});
        const Overlap o = overlapOf(a, b);
        const double exact = (4 * r + d) * (2 * r - d) * (2 * r - d) / (16 * r * r * r);
        EXPECT_NEAR(o.dice(), exact, 2e-3) << d;
    }
}

TEST(OverlapVolume, SurfacesThatCoincideInPartStillCompare) {
    // Shared faces, edges and vertices: corefinement builds no solid of
    // them ("not a manifold solid", or CGAL's "Unauthorized intersections of
    // constraints"), and Brodmann neighbours, a mesh against itself and
    // against its simplification all ended in exit 3.
    struct Pair {
        const char* what;
        TriangleSoup a, b;
        double intersectionMm3;  // < 0: all of A
    };
    const Pair pairs[] = {
        {"a box and itself", boxMesh({0, 0, 0}, {10, 10, 10}, 3),
         boxMesh({0, 0, 0}, {10, 10, 10}, 3), 1000},
        {"a sphere and itself", geodesicSphere(16, 10), geodesicSphere(16, 10), -1},
        {"boxes sharing a face, side by side", boxMesh({0, 0, 0}, {10, 10, 10}, 3),
         boxMesh({10, 0, 0}, {20, 10, 10}, 2), 0},
        {"a half box inside, sharing five faces", boxMesh({0, 0, 0}, {10, 10, 10}, 2),
         boxMesh({0, 0, 0}, {5, 10, 10}, 2), 500},
        {"boxes sharing an edge", boxMesh({0, 0, 0}, {10, 10, 10}, 1),
         boxMesh({10, 10, 0}, {20, 20, 10}, 1), 0},
        {"boxes sharing a vertex", boxMesh({0, 0, 0}, {10, 10, 10}, 1),
         boxMesh({10, 10, 10}, {20, 20, 20}, 1), 0},
    };
    for (const Pair& p : pairs) {
        const Overlap o = overlapOf(p.a, p.b);
        const double exact = p.intersectionMm3 < 0 ? o.volumeAMm3 : p.intersectionMm3;
        EXPECT_NEAR(o.intersectionMm3, exact, o.intersectionBoundMm3 + 1e-9) << p.what;
        EXPECT_LE(o.intersectionBoundMm3, 1e-3) << p.what;  // area · 1e-6 mm, here
        EXPECT_EQ(std::string(o.method), o.shiftMm > 0 ? "surface flux, B shifted" : "exact")
            << p.what;
    }
}

TEST(OverlapVolume, AShiftOfBChangesTheIntersectionByAtMostAreaTimesShift) {
    // The bound the shifted fallback reports: moving B by s sweeps at most
    // area(B)·s of volume in or out of A.
    const TriangleSoup a = geodesicSphere(24, 10), b = geodesicSphere(24, 10, {6, 0, 0});
    const double areaB = checkMesh(b).areaMm2;
    const double unshifted = intersectionVolume(a, b, {0, 0, 0}).value();
    for (const double s : {1e-6, 1e-3, 0.1}) {
        const Vec3 shift = (s / std::sqrt(3.0)) * Vec3{1, 1, 1};
        const double moved = intersectionVolume(a, b, shift).value();
        EXPECT_LE(std::abs(moved - unshifted), areaB * s) << s;
    }
    // And a shift of the lens along the axis changes it as the lens formula says.
    const double r = 10, d0 = 6, ds = 0.1;
    const auto lens = [&](double d) { return M_PI * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12; };
    const double change = intersectionVolume(a, b, {ds, 0, 0}).value() - unshifted;
    EXPECT_NEAR(change, lens(d0 + ds) - lens(d0), 0.05 * std::abs(lens(d0 + ds) - lens(d0)));
}

TEST(OverlapVolume, RefusesWhatIsNoSolid) {
    TriangleSoup open = boxMesh({0, 0, 0}, {1, 1, 1}, 1);
    open.triangles.pop_back();
    EXPECT_THROW(overlapOf(open, boxMesh({0, 0, 0}, {1, 1, 1}, 1)), std::invalid_argument);
}

TEST(SurfaceDistances, NestedBoxesAreExactlyDApart) {
    const double d = 1.5;
    const TriangleSoup inner = boxMesh({0, 0, 0}, {10, 10, 10}, 3);
    const TriangleSoup outer = boxMesh({-d, -d, -d}, {10 + d, 10 + d, 10 + d}, 2);
    const SurfaceDistances s = surfaceDistances(inner, outer, 0.25);
    // From the inner surface every point is exactly d from the outer one.
    EXPECT_NEAR(s.aToB.maxMm, d, 1e-9);
    EXPECT_NEAR(s.aToB.meanMm, d, 1e-9);
    EXPECT_NEAR(s.aToB.p95Mm, d, 1e-9);
    // From the outer surface, up to d√3 at its corners.
    EXPECT_LE(s.bToA.maxMm, d * std::sqrt(3.0) + 1e-9);
    EXPECT_GE(s.bToA.maxMm, d * std::sqrt(3.0) - s.spacingMm);
    EXPECT_NEAR(s.hausdorffMm(), s.bToA.maxMm, 1e-12);
    EXPECT_NEAR(s.areaAMm2, 600, 1e-9);
    EXPECT_NEAR(s.areaBMm2, 6 * (10 + 2 * d) * (10 + 2 * d), 1e-9);
}

TEST(SurfaceDistances, IdenticalSurfacesAreZeroApart) {
    const TriangleSoup a = geodesicSphere(8, 5);
    const SurfaceDistances s = surfaceDistances(a, a, 0.5);
    EXPECT_LT(s.hausdorffMm(), 1e-9);
    EXPECT_LT(s.meanMm(), 1e-9);
}

namespace {

// Surface Dice by brute force: `perTriangle` random points on every
// triangle of each surface, each weighted by its triangle's area, with its
// distance to every triangle of the other. O(points · triangles).
double bruteForceSurfaceDice(const TriangleSoup& a, const TriangleSoup& b, double toleranceMm,
                             int perTriangle) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0, 1);
    double within = 0, total = 0;
    for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}})
        for (const auto& t : from->triangles) {
            const Vec3 p0 = from->points[t[0]], p1 = from->points[t[1]], p2 = from->points[t[2]];
            const double weight = 0.5 * length(cross(p1 - p0, p2 - p0)) / perTriangle;
            for (int k = 0; k < perTriangle; ++k) {
                double u = unit(random), v = unit(random);
                if (u + v > 1) u = 1 - u, v = 1 - v;
                const Vec3 p = p0 + u * (p1 - p0) + v * (p2 - p0);
                double nearest = INFINITY;
                for (const auto& s : to->triangles)
                    nearest = std::min(nearest,
                                       pointTriangleDistance(p, to->points[s[0]], to->points[s[1]],
                                                             to->points[s[2]]));
                within += nearest <= toleranceMm ? weight : 0;
                total += weight;
            }
        }
    return within / total;
}

}  // namespace

TEST(SurfaceDistances, SurfaceDiceAgreesWithBruteForce) {
    // Offset spheres: part of each surface inside the other's tolerance band.
    const TriangleSoup a = geodesicSphere(6, 10), b = geodesicSphere(6, 9, {3, 0, 0});
    const double spacing = 0.2;
    for (const double tolerance : {0.5, 1.0, 2.0}) {
        const SurfaceDistances s = surfaceDistances(a, b, spacing, tolerance);
        // Each sample stands for its cell, points within `spacing`:
        // the figure lies between the exact ones at τ ∓ spacing (and the
        // random reference's noise, some 0.01 at this count).
        const double lower = bruteForceSurfaceDice(a, b, tolerance - spacing, 40) - 0.015;
        const double upper = bruteForceSurfaceDice(a, b, tolerance + spacing, 40) + 0.015;
        EXPECT_GE(s.surfaceDice(), lower) << tolerance;
        EXPECT_LE(s.surfaceDice(), upper) << tolerance;
        EXPECT_GT(upper - lower, 0) << tolerance;
    }
}

TEST(SurfaceDistances, ConcentricSurfacesAreAllAtOneDistance) {
    // Nested boxes d apart: every point of the inner one exactly d from the
    // outer; surface Dice is 0 below d, pooled HD95 between the two
    // directions' own.
    const double d = 1.5;
    const TriangleSoup inner = boxMesh({0, 0, 0}, {10, 10, 10}, 3);
    const TriangleSoup outer = boxMesh({-d, -d, -d}, {10 + d, 10 + d, 10 + d}, 2);
    const SurfaceDistances below = surfaceDistances(inner, outer, 0.25, d - 0.3);
    EXPECT_EQ(below.surfaceDice(), 0);
    const SurfaceDistances above = surfaceDistances(inner, outer, 0.25, d * std::sqrt(3.0) + 0.3);
    EXPECT_NEAR(above.surfaceDice(), 1, 1e-12);
    EXPECT_GE(above.hd95PooledMm, std::min(above.aToB.p95Mm, above.bToA.p95Mm));
    EXPECT_LE(above.hd95PooledMm, above.hd95Mm());
    EXPECT_NEAR(above.aToB.p95Mm, d, 1e-9);
}

// The cells of `soup` at spacingMm, every one counted.
std::size_t cellCount(const TriangleSoup& soup, double spacingMm) {
    std::size_t count = 0;
    for (const auto& t : soup.triangles)
        forEachCell(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]], spacingMm,
                    [&](const Vec3&, double) { ++count; });
    return count;
}

TEST(SurfaceDistances, ACellWalkStopsWhereItsVisitSaysSo) {
    const Vec3 p0{0, 0, 0}, p1{10, 0, 0}, p2{0, 7, 0};
    std::size_t all = 0;
    double areaMm2 = 0;
    EXPECT_TRUE(forEachCellWhile(p0, p1, p2, 0.1, [&](const Vec3&, double weightMm2) {
        ++all;
        areaMm2 += weightMm2;
        return true;
    }));
    EXPECT_NEAR(areaMm2, 35, 1e-9);
    ASSERT_GT(all, 1000u);
    std::size_t visited = 0;
    EXPECT_FALSE(
        forEachCellWhile(p0, p1, p2, 0.1, [&](const Vec3&, double) { return ++visited < 1000; }));
    EXPECT_EQ(visited, 1000u);
}

TEST(SurfaceDistances, ABudgetBelowTheTrianglesStopsAtOneCellPerTriangle) {
    // More triangles than the budget allows cells: no spacing gives fewer
    // than one cell per triangle, and the search returned (it grew the
    // spacing for ever before) at a spacing where each is one cell.
    const TriangleSoup sphere = geodesicSphere(16, 10);
    const std::size_t budget = sphere.triangles.size() / 4;
    const double spacing = cellSpacingWithinBudget({&sphere}, 0.01, budget);
    std::size_t cells = 0;
    for (const auto& t : sphere.triangles)
        forEachCell(sphere.points[t[0]], sphere.points[t[1]], sphere.points[t[2]], spacing,
                    [&](const Vec3&, double) { ++cells; });
    EXPECT_EQ(cells, sphere.triangles.size());
    EXPECT_TRUE(std::isfinite(spacing));
    // And the distances of a surface to itself at that spacing are zero.
    const SurfaceDistances self = surfaceDistances(sphere, sphere, spacing);
    EXPECT_NEAR(self.hausdorffMm(), 0.0, 1e-12);
}

TEST(SurfaceDistances, CellsCoverTheirTriangleWithinTheSpacingAndAreFew) {
    // Well-shaped, right, obtuse and needle triangles: the weights sum to the
    // area; every point of the triangle (random, brute force) lies within the
    // spacing of some sample; and the cells are few — within 1.6× (thin
    // slivers 1.5×) of the fewest any cutting could give, plus 2.
    struct Case {
        Vec3 p0, p1, p2;
        bool sliver;
    };
    const Case cases[] = {{{0, 0, 0}, {10, 0, 0}, {5, 8.66, 0}, false},
                          {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, false},
                          {{0, 0, 0}, {7, 0, 0}, {2, 4, 3}, false},
                          {{0, 0, 0}, {2, 0, 0}, {1, 0.1, 0}, true},          // flat, obtuse
                          {{0, 0, 0}, {2, 0.02, 0.3}, {2, 0.12, 0.1}, true},  // needle
                          {{1, 1, 1}, {1.5, 1, 1}, {1.25, 3, 1.5}, false}};   // tall
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (const double s : {0.2, 0.5}) {
        for (const Case& c : cases) {
            std::vector<Vec3> samples;
            double areaMm2 = 0;
            forEachCell(c.p0, c.p1, c.p2, s, [&](const Vec3& p, double w) {
                samples.push_back(p);
                areaMm2 += w;
            });
            const double exactArea = 0.5 * length(cross(c.p1 - c.p0, c.p2 - c.p0));
            EXPECT_NEAR(areaMm2, exactArea, 1e-9 * exactArea);
            for (int k = 0; k < 2000; ++k) {
                double u = unit(random), v = unit(random);
                if (u + v > 1) u = 1 - u, v = 1 - v;
                const Vec3 x = c.p0 + u * (c.p1 - c.p0) + v * (c.p2 - c.p0);
                double nearest = INFINITY;
                for (const Vec3& p : samples) nearest = std::min(nearest, length(x - p));
                ASSERT_LE(nearest, s * (1 + 1e-9));
            }
            const double longest =
                std::max({length(c.p1 - c.p0), length(c.p2 - c.p1), length(c.p0 - c.p2)});
            // No cell can be larger than an equilateral one of circumradius
            // s, nor longer than 2s.
            const double fewest =
                std::max(exactArea / (0.75 * std::sqrt(3.0) * s * s), longest / (2 * s));
            EXPECT_LE(double(samples.size()), (c.sliver ? 1.5 : 1.6) * fewest + 2)
                << s << " " << c.p2.x;
        }
    }
}

TEST(SurfaceDistances, ASpacingOverTheSampleBudgetIsCoarsenedToJustWithinIt) {
    // A metre cube at 0.2 mm: about 1.5·10^8 cells a surface, which the
    // budget search no longer counts one by one.
    const TriangleSoup cube = boxMesh({0, 0, 0}, {1000, 1000, 1000}, 1);
    const double spacing = distanceSpacingWithinBudget(cube, cube, 0.2);
    EXPECT_GT(spacing, 0.2);
    const std::size_t cells = cellCount(cube, spacing);
    EXPECT_LE(cells, kMaxDistanceSamples);
    // Not coarser than it needs to be: a right triangle's cells halve in
    // number with each longest-edge halving level, so the first spacing
    // within the budget holds more than a quarter of it.
    EXPECT_GT(cells, kMaxDistanceSamples / 4);
    EXPECT_GT(cellCount(cube, spacing / 1.5), kMaxDistanceSamples);
    // Within the budget the asked spacing is the one used.
    const TriangleSoup small = boxMesh({0, 0, 0}, {10, 10, 10}, 2);
    EXPECT_EQ(distanceSpacingWithinBudget(small, cube, 50.0), 50.0);
    EXPECT_EQ(distanceSpacingWithinBudget(small, small, 0.25), 0.25);
}

TEST(SurfaceDistances, DeviceAgreesWithTheHostReference) {
    // The closest-primitive kernel against its C++ twin (a host hierarchy):
    // the same samples, distances equal to rounding in double precision and
    // within the kernel's stated tolerance in single; every figure alike.
    static ocl::Runtime runtime;
    const TriangleSoup a = geodesicSphere(5, 10), b = boxMesh({-4, -3, -2}, {9, 8, 7}, 5);
    for (const double spacing : {0.3, 1.0}) {
        const SurfaceDistances host = surfaceDistances(a, b, spacing, 1.0);
        const SurfaceDistances device = surfaceDistances(runtime, a, b, spacing, 1.0);
        const double tolerance = runtime.device().doublePrecision ? 1e-9 : 1e-4;
        EXPECT_EQ(host.aToB.samples, device.aToB.samples);
        EXPECT_EQ(host.bToA.samples, device.bToA.samples);
        EXPECT_NEAR(host.hausdorffMm(), device.hausdorffMm(), tolerance);
        EXPECT_NEAR(host.hd95Mm(), device.hd95Mm(), tolerance);
        EXPECT_NEAR(host.hd95PooledMm, device.hd95PooledMm, tolerance);
        EXPECT_NEAR(host.meanMm(), device.meanMm(), tolerance);
        EXPECT_NEAR(host.surfaceDice(), device.surfaceDice(), 1e-3);
    }
}

TEST(SurfaceDistances, CellsCoverEveryPointWithinTheSpacing) {
    // Hausdorff of a surface against itself shifted by d is at most d, and
    // at least d minus the spacing wherever the surfaces run parallel: for
    // a box moved along x, its faces x = const are exactly d apart.
    const TriangleSoup a = boxMesh({0, 0, 0}, {10, 10, 10}, 1);  // large, thin cells
    const TriangleSoup b = boxMesh({0.7, 0, 0}, {10.7, 10, 10}, 1);
    for (const double spacing : {0.1, 0.5, 2.0}) {
        const SurfaceDistances d = surfaceDistances(a, b, spacing);
        EXPECT_LE(d.hausdorffMm(), 0.7 + 1e-12) << spacing;
        EXPECT_GE(d.hausdorffMm(), 0.7 - spacing) << spacing;
        EXPECT_NEAR(d.areaAMm2, 600, 1e-9);
    }
}

TEST(SurfaceMeasures, CentroidsOfBoxesAndSpheres) {
    const SurfaceMeasures box = measureSurface(boxMesh({2, 4, 6}, {4, 8, 12}, 3));
    EXPECT_NEAR(length(box.centroidMm - Vec3{3, 6, 9}), 0, 1e-12);
    const SurfaceMeasures ball = measureSurface(geodesicSphere(8, 5, {1, -2, 7}));
    EXPECT_NEAR(length(ball.centroidMm - Vec3{1, -2, 7}), 0, 1e-9);
}
