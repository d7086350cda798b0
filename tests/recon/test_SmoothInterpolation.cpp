// Smooth interpolation between planes: the interpolant against its defining
// properties, and smooth reconstructions against analytic surfaces (exact
// signed distances), their linear counterparts and the contour points.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "recon/HermiteTangents.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/SlabVolumes.hpp"
#include "recon/SliceInterpolant.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/SimplificationVerifier.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

double meanDistance(const AnalyticShape& shape, const TriangleSoup& soup, double zLo, double zHi) {
    double sum = 0;
    std::size_t count = 0;
    for (const Vec3& p : sampleTriangles(soup, 20000, 5))
        if (p.z >= zLo && p.z <= zHi) sum += std::abs(shape.signedDistance(p)), ++count;
    return sum / double(std::max<std::size_t>(1, count));
}

/// A synth shape sliced `spacingMm` apart and reconstructed both ways.
struct BothModes {
    std::unique_ptr<AnalyticShape> shape;
    ContourSet set;
    Reconstruction linear, smooth;
    const Roi& roi() const { return set.rois[0]; }
};

BothModes reconstructBothWays(const char* name, double spacingMm) {
    BothModes both;
    both.shape = makeShape(name);
    SynthOptions options;
    options.spacingMm = spacingMm;
    both.set = sliceShape(*both.shape, options);
    ReconstructionOptions linear;
    linear.interpolation = Interpolation::Linear;
    both.linear = reconstructSurface(cpuRuntime(), both.roi(), linear);
    both.smooth = reconstructSurface(cpuRuntime(), both.roi());
    return both;
}

}  // namespace

// Fields made by hand on a 4 × 4 grid of 1 mm pixels: `value(i, j, s)` at
// pixel (i, j) of plane s.
template <class Value>
SliceFields handMadeFields(const std::vector<double>& zMm, Value value) {
    SliceFields fields;
    fields.grid.originMm = {-2, -2};
    fields.grid.pixelMm = 1;
    fields.grid.width = fields.grid.height = 4;
    fields.zMm = zMm;
    for (std::size_t s = 0; s < zMm.size(); ++s)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                fields.distanceMm.push_back(float(value(i, j, s)));
                fields.nearestId.push_back(kNoPrimitive);
            }
    return fields;
}

// At every pixel centre, a quadratic in z whose coefficients vary over the
// grid, on unevenly spaced planes.
SliceFields quadraticFields(const std::vector<double>& zMm) {
    return handMadeFields(zMm, [&](int i, int j, std::size_t s) {
        return 0.5 * i - j + (0.3 - 0.1 * j) * zMm[s] + 0.05 * i * zMm[s] * zMm[s];
    });
}

double quadraticAt(int i, int j, double z) {
    return 0.5 * i - j + (0.3 - 0.1 * j) * z + 0.05 * i * z * z;
}

TEST(SliceInterpolant, EqualsEachPlaneReproducesQuadraticsAndIsC1) {
    const std::vector<double> z{0, 1.5, 4, 5, 7.5};
    const SliceFields fields = quadraticFields(z);
    SliceInterpolant field(fields);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Point2 c = fields.grid.pixelCentre(i, j);
            for (std::size_t s = 0; s < z.size(); ++s)
                EXPECT_NEAR(field.value({c.x, c.y, z[s]}), quadraticAt(i, j, z[s]), 1e-5);
            // Between planes whose tangents both come from parabolas (not the
            // stack's end slabs): the quadratic itself, which bulges beyond
            // both planes' values where it turns (a monotone cubic cannot).
            for (double zz : {1.7, 2.5, 3.9, 4.3, 4.8})
                EXPECT_NEAR(field.value({c.x, c.y, zz}), quadraticAt(i, j, zz), 1e-5) << zz;
            // C1 across an inner plane: one-sided slopes agree.
            const double d = 1e-4;
            const double below = (field.value({c.x, c.y, 4}) - field.value({c.x, c.y, 4 - d})) / d;
            const double above = (field.value({c.x, c.y, 4 + d}) - field.value({c.x, c.y, 4})) / d;
            EXPECT_NEAR(below, above, 1e-3);
        }
}

// The same value at every pixel of a plane, one value per plane.
SliceFields uniformFields(const std::vector<double>& zMm, const std::vector<double>& values) {
    return handMadeFields(zMm, [&](int, int, std::size_t s) { return values[s]; });
}

TEST(HermiteTangents, EndTangentsFollowTheEndSlabsParabolaWithinBounds) {
    // A cone's end: the inner tangent equals the secant, and so does the end's.
    EXPECT_DOUBLE_EQ(endTangent(1, 1), 1);
    // The widest section at the inner plane (tangent 0): twice the secant,
    // the parabola's slope at its end; either sign.
    EXPECT_DOUBLE_EQ(endTangent(1, 0), 2);
    EXPECT_DOUBLE_EQ(endTangent(-0.5, 0), -1);
    // At most twice the secant (the parabola whose vertex is the inner
    // plane); never across 0 (an end that closes stays one that closes).
    EXPECT_DOUBLE_EQ(endTangent(1, -5), 2);
    EXPECT_DOUBLE_EQ(endTangent(1, 0.5), 1.5);
    EXPECT_DOUBLE_EQ(endTangent(1, 3), 0);
    // Inside: a weighted mean of the secants, each weighted by the other
    // slab's height (the parabola's slope at the plane).
    EXPECT_DOUBLE_EQ(parabolaTangent(1, 1, 2, 4), (2 * 1 + 1 * 4) / 3.0);
    EXPECT_TRUE(flatBeside(0.04, 1));
    EXPECT_FALSE(flatBeside(0.06, 1));
}

TEST(HermiteTangents, InnerTangentIsTheParabolaBesideNoStraightStretch) {
    const auto none = [] { return std::optional<double>(); };
    const auto flat = [] { return std::optional<double>(0.0); };
    const auto steep = [] { return std::optional<double>(3.0); };
    // Trusted whole: the parabola's slope, bit for bit.
    EXPECT_EQ(innerTangent(1, 1, 2, 4, none, none), parabolaTangent(1, 1, 2, 4));
    // A flat slab below with another flat one beyond it: a straight stretch.
    EXPECT_EQ(innerTangent(1, 0, 1, 2, flat, none), 0);
    // One flat slab alone (the next one changes, or the stack ends there).
    EXPECT_EQ(innerTangent(1, 0, 1, 2, steep, none), 1);
    EXPECT_EQ(innerTangent(1, 0, 1, 2, none, none), 1);
    // Likewise above.
    EXPECT_EQ(innerTangent(1, 2, 1, 0, none, flat), 0);
    // A secant trusted at 0.3 weighs 0.3 of the other: (0.3·(-1) + 2) / 1.3.
    EXPECT_DOUBLE_EQ(innerTangent(2, -1, 2, 2, none, none, 0.3, 1), (0.3 * -1 + 2) / 1.3);
}

TEST(SliceInterpolant, AStraightStretchEndsStraightWhereTheChangeBegins) {
    // Three equal planes (a stem), then the field changes (a branching): the
    // stem's last slab stays exactly straight, and the slope is 0 on both
    // sides of its last plane, so the change is C1 too.
    const SliceFields stem = uniformFields({0, 1, 2, 3, 4}, {-2, -2, -2, 1, 1.5});
    const SliceInterpolant field(stem);
    for (double z : {1.1, 1.5, 1.9}) EXPECT_NEAR(field.value({0, 0, z}), -2, 1e-6) << z;
    const double d = 1e-4;
    EXPECT_NEAR((field.value({0, 0, 2 + d}) - field.value({0, 0, 2})) / d, 0, 1e-3);
    // One flat slab between two changing ones is a bulge symmetric about its
    // middle (f = z² on planes -3, -1, 1, 3), not a straight stretch: the
    // parabola's slopes stay, and the interpolant is the quadratic itself.
    const SliceFields bulge = uniformFields({-3, -1, 1, 3}, {9, 1, 1, 9});
    const SliceInterpolant round(bulge);
    for (double z : {-0.5, 0.0, 0.7}) EXPECT_NEAR(round.value({0, 0, z}), z * z, 1e-6) << z;
}

TEST(SliceInterpolant, ANeighboursFarFaceCountsLessInTheTangent) {
    // A thin tilted plate: on plane s (z = 2s) the band |x - 5.5 s| <= 4.4,
    // so its lower face runs straight from x = -4.4 at z = 0 by 2.75 mm per
    // mm of z. Mid-slab between z = 2 and 4 the face is at x = 3.85; there
    // plane 0's field measures the band's far edge (its gradient points the
    // other way), and the plain parabola's tangent at z = 2 is 0.825 where
    // the face's is 2.75: F = -0.48 on the true face. That secant now counts
    // at 0.3: F = 0.25 (0.3 (-1.1) + 2.75) / 1.3 - 0.25 * 2.75 = -0.222.
    SliceFields bands;
    bands.grid.originMm = {-10, -0.2};
    bands.grid.pixelMm = 0.1;
    bands.grid.width = 400;
    bands.grid.height = 4;
    bands.zMm = {0, 2, 4, 6};
    for (std::size_t s = 0; s < bands.zMm.size(); ++s)
        for (int j = 0; j < bands.grid.height; ++j)
            for (int i = 0; i < bands.grid.width; ++i) {
                const double x = bands.grid.pixelCentre(i, j).x;
                bands.distanceMm.push_back(float(std::abs(x - 5.5 * double(s)) - 4.4));
                bands.nearestId.push_back(kNoPrimitive);
            }
    const SliceInterpolant field(bands);
    const double plainParabola = 0.25 * (parabolaTangent(2, -1.1, 2, 2.75) - 2.75);
    EXPECT_NEAR(plainParabola, -0.48125, 1e-9);
    const double onFace = field.value({3.85, 0, 3});
    EXPECT_NEAR(onFace, 0.25 * ((0.3 * -1.1 + 2.75) / 1.3 - 2.75), 1e-3);
    EXPECT_LT(std::abs(onFace), 0.5 * std::abs(plainParabola));
    // Where every plane read sees the same face (the lowest slab's lower
    // face, x = -1.65 at z = 1: the end slab's secant, then the parabola
    // through three distances to that face) nothing changes: a straight
    // face is the face.
    EXPECT_NEAR(field.value({-1.65, 0, 1}), 0, 1e-3);
}

TEST(SmoothInterpolation, CloserToRoundShapesThroughEveryContourPointAndValid) {
    for (const char* name : {"sphere", "ellipsoid", "hollow-sphere"})
        for (double spacing : {2.0, 5.0}) {
            const BothModes both = reconstructBothWays(name, spacing);
            const AnalyticShape* shape = both.shape.get();
            const Roi& roi = both.roi();
            const Reconstruction &linear = both.linear, &smooth = both.smooth;
            const std::string label = std::string(name) + " " + std::to_string(spacing);
            ASSERT_TRUE(smooth.check.validSolid()) << label;
            EXPECT_TRUE(checkMesh(smooth.surface).validSolid()) << label;
            EXPECT_FALSE(smooth.stats.smoothFellBack) << label;
            EXPECT_GT(smooth.stats.smoothedVertices, 0u) << label;
            // Every contour point is a vertex (to float precision).
            std::set<std::tuple<float, float, float>> vertices;
            for (const Vec3& p : smooth.surface.points)
                vertices.insert({float(p.x), float(p.y), float(p.z)});
            for (const Slice& slice : roi.slices)
                for (const Polygon& contour : slice.contours)
                    for (Point2 p : contour)
                        ASSERT_TRUE(vertices.count({float(p.x), float(p.y), float(slice.zMm)}))
                            << label;
            // Between the first and last plane (the caps are the same in
            // both modes), closer to the true surface than straight strips.
            const double lo = roi.slices.front().zMm, hi = roi.slices.back().zMm;
            const double smoothMean = meanDistance(*shape, smooth.surface, lo, hi);
            const double linearMean = meanDistance(*shape, linear.surface, lo, hi);
            EXPECT_LT(smoothMean, linearMean) << label;
            // Straight strips cut inside a round shape; smooth mode does not
            // lose its volume (the exact one: caps at half a spacing follow
            // the planning-system convention, so allow what they add).
            const double exact = shape->volumeMm3();
            EXPECT_LT(std::abs(smooth.check.volumeMm3 / exact - 1),
                      std::abs(linear.check.volumeMm3 / exact - 1))
                << label;
            EXPECT_LT(std::abs(smooth.check.volumeMm3 / exact - 1), 0.015) << label;
        }
}

TEST(SlabVolumes, HermiteAreaRatioFollowsTheSectionsTrend) {
    // A ball's section area is quadratic in z, which the parabola tangents
    // reproduce between inner planes: the ratio is the exact area over the
    // straight mean there.
    PlaneSections ball;
    for (double z = -15; z <= 15; z += 5) {
        ball.zMm.push_back(z);
        ball.areaMm2.push_back(kPi * (400 - z * z));
        ball.perimeterMm.push_back(2 * kPi * std::sqrt(400 - z * z));
    }
    for (double z : {-8.0, -2.5, 1.0, 7.5}) {
        const double z0 = 5 * std::floor(z / 5), t = (z - z0) / 5;
        const double straight = kPi * ((1 - t) * (400 - z0 * z0) + t * (400 - (z0 + 5) * (z0 + 5)));
        EXPECT_NEAR(hermiteAreaRatio(ball, z), kPi * (400 - z * z) / straight, 1e-9) << z;
        EXPECT_GT(hermiteAreaRatio(ball, z), 1) << z;  // convex: above the chord
    }
    // A waist between two planes: less than the straight mean half-way.
    const PlaneSections waist{{0, 5, 10, 15}, {300, 100, 100, 300}, {62, 36, 36, 62}};
    EXPECT_LT(hermiteAreaRatio(waist, 7.5), 0.9);
    EXPECT_GE(hermiteAreaRatio(waist, 7.5), kMinAreaRatio);
    // Outside the stack, and with one plane, the straight mean stands.
    EXPECT_EQ(hermiteAreaRatio(waist, -1), 1);
    EXPECT_EQ(hermiteAreaRatio(waist, 16), 1);
    EXPECT_EQ(hermiteAreaRatio(PlaneSections{{0}, {10}, {12}}, 0), 1);
}

TEST(SlabVolumes, AComponentsTargetsEndWhereItsSectionsDo) {
    // A component with sections on planes 2-4 of 0-6 (it begins and ends
    // mid-stack, under caps of its own): its slabs' targets are those of its
    // own stack, whose ends take the end slab's secant; the empty planes
    // around it do not bend its areas toward zero.
    const PlaneSections all{
        {0, 2, 4, 6, 8, 10, 12}, {0, 0, 100, 160, 120, 0, 0}, {0, 0, 36, 45, 39, 0, 0}};
    const PlaneSections own{{4, 6, 8}, {100, 160, 120}, {36, 45, 39}};
    const std::vector<double> targets = ownVolumeTargets(all);
    const std::vector<double> expected = slabVolumeTargets(own);
    ASSERT_EQ(targets.size(), 6u);
    EXPECT_EQ(targets[0], 0);
    EXPECT_EQ(targets[1], 0);
    EXPECT_DOUBLE_EQ(targets[2], expected[0]);
    EXPECT_DOUBLE_EQ(targets[3], expected[1]);
    EXPECT_EQ(targets[4], 0);
    EXPECT_EQ(targets[5], 0);
    // Taken over the whole stack, the empty planes would pull the tangents:
    // more volume than the sections' own trend.
    EXPECT_GT(slabVolumeTargets(all)[2], expected[0]);
}

TEST(SmoothInterpolation, SlabVolumesMatchTheirTargets) {
    // The volume matching itself: between the end planes, each slab of the
    // smooth surface holds the C1 integral of its planes' areas.
    SynthOptions options;
    options.spacingMm = 3;
    const ContourSet set = sliceShape(*makeShape("ellipsoid"), options);
    const Roi& roi = set.rois[0];
    const Reconstruction smooth = reconstructSurface(cpuRuntime(), roi);
    ASSERT_TRUE(smooth.check.validSolid());
    const PlaneSections planes = sectionsOf(roi.slices);
    const std::vector<double> targets = slabVolumeTargets(planes);
    double target = 0;
    for (double t : targets) target += t;
    const double between = volumeBelowPlane(smooth.surface, planes.zMm.back()) -
                           volumeBelowPlane(smooth.surface, planes.zMm.front());
    EXPECT_NEAR(between / target, 1, 2e-3);
}

TEST(SmoothInterpolation, ACavityWallFollowsTheCavitysOwnProfile) {
    // A cavity's wall is a part of its slabs of its own (hole contours): it
    // bulges by the cavity's own profile, not by the solid's bulge around it,
    // which would move it into the cavity where the cavity widens. Measured
    // on the wall alone (samples nearer the cavity's sphere than the outer
    // one) against the exact surface: much closer than the straight wall.
    for (double spacing : {2.0, 5.0}) {
        const BothModes both = reconstructBothWays("hollow-sphere", spacing);  // r 20, cavity r 10
        const AnalyticShape* shape = both.shape.get();
        const Roi& roi = both.roi();
        const Reconstruction &linear = both.linear, &smooth = both.smooth;
        ASSERT_TRUE(smooth.check.validSolid()) << spacing;
        ASSERT_FALSE(smooth.stats.smoothFellBack) << spacing;
        auto cavityWallMean = [&](const TriangleSoup& soup) {
            double sum = 0;
            std::size_t count = 0;
            for (const Vec3& p : sampleTriangles(soup, 40000, 7))
                if (length(p) < 15 && p.z >= roi.slices.front().zMm && p.z <= roi.slices.back().zMm)
                    sum += std::abs(shape->signedDistance(p)), ++count;
            EXPECT_GT(count, 1000u);
            return sum / double(std::max<std::size_t>(count, 1));
        };
        const double smoothMean = cavityWallMean(smooth.surface);
        const double linearMean = cavityWallMean(linear.surface);
        // 2 mm: 0.038 against 0.074 mm (0.065 with the solid's bulge); at
        // 5 mm the cavity's caps, which stay flat, weigh as much as its wall.
        EXPECT_LT(smoothMean, (spacing < 3 ? 0.6 : 1.0) * linearMean) << spacing;
    }
}

TEST(SmoothInterpolation, SeparateObjectsOfOneRoiEachBulgeByTheirOwnSections) {
    // Two balls of one ROI side by side (r 12 and 9 mm, their poles on
    // different planes): one bulge per slab for both sized the smaller ball
    // near its pole by the larger one's sections. Each is a component of the
    // surface and bulges by its own sections: both lie much closer to the
    // exact balls than straight strips do.
    for (double spacing : {2.0, 5.0}) {
        const BothModes both = reconstructBothWays("two-blobs", spacing);
        const Roi& roi = both.roi();
        const Reconstruction &linear = both.linear, &smooth = both.smooth;
        ASSERT_TRUE(smooth.check.validSolid()) << spacing;
        ASSERT_FALSE(smooth.stats.smoothFellBack) << spacing;
        EXPECT_EQ(smooth.check.components, 2u);
        const double lo = roi.slices.front().zMm, hi = roi.slices.back().zMm;
        const double smoothMean = meanDistance(*both.shape, smooth.surface, lo, hi);
        const double linearMean = meanDistance(*both.shape, linear.surface, lo, hi);
        // 0.43 and 0.36 of the straight strips' distance at 2 and 5 mm; with
        // one bulge per slab for both, 0.94 and 0.90.
        EXPECT_LT(smoothMean, 0.6 * linearMean) << spacing;
    }
}

}  // namespace dfrecon

namespace dfrecon {

TEST(SmoothInterpolation, RingsAreThinnedWhereTheSurfaceLetsThem) {
    // Refinement splits every sagging rung, so its rings have a vertex per
    // rung; thinning merges ring neighbours where the merged triangles stay
    // within the tolerance. Against the same surface with every ring vertex
    // kept: fewer triangles, as close to the exact shape (the samples'
    // largest distance within the tolerance of it), the same volume to 0.2 %,
    // and a report that a whole check of the result confirms.
    std::size_t fullTriangles = 0, thinTriangles = 0;
    for (const char* name : {"sphere", "two-blobs", "hollow-sphere", "branch", "torus-30"}) {
        const auto shape = makeShape(name);
        SynthOptions slicing;
        slicing.spacingMm = 2;
        const ContourSet set = sliceShape(*shape, slicing);
        const Roi& roi = set.rois[0];
        ReconstructionOptions keepAll;
        keepAll.coarsenRings = false;
        const Reconstruction full = reconstructSurface(cpuRuntime(), roi, keepAll);
        const Reconstruction thin = reconstructSurface(cpuRuntime(), roi);
        ASSERT_TRUE(full.check.validSolid()) << name;
        ASSERT_TRUE(thin.check.validSolid()) << name;
        EXPECT_GT(thin.stats.smoothCoarsenedVertices, 0u) << name;
        EXPECT_LT(thin.surface.triangles.size(), full.surface.triangles.size()) << name;
        fullTriangles += full.surface.triangles.size();
        thinTriangles += thin.surface.triangles.size();

        const MeshCheckReport whole = checkMesh(thin.surface);
        EXPECT_TRUE(whole.validSolid()) << name;
        EXPECT_EQ(whole.vertices, thin.check.vertices) << name;
        EXPECT_EQ(whole.edges, thin.check.edges) << name;
        EXPECT_EQ(whole.triangles, thin.check.triangles) << name;
        EXPECT_EQ(whole.components, thin.check.components) << name;
        EXPECT_EQ(whole.genus, thin.check.genus) << name;
        EXPECT_NEAR(whole.volumeMm3, thin.check.volumeMm3, 1e-6 * whole.volumeMm3) << name;
        EXPECT_NEAR(thin.check.volumeMm3 / full.check.volumeMm3, 1, 2e-3) << name;

        const double lo = roi.slices.front().zMm, hi = roi.slices.back().zMm;
        auto farthest = [&](const TriangleSoup& soup) {
            double most = 0;
            for (const Vec3& p : sampleTriangles(soup, 40000, 3))
                if (p.z >= lo && p.z <= hi)
                    most = std::max(most, std::abs(shape->signedDistance(p)));
            return most;
        };
        EXPECT_LE(farthest(thin.surface), farthest(full.surface) + 0.05) << name;
        EXPECT_LT(meanDistance(*shape, thin.surface, lo, hi),
                  1.1 * meanDistance(*shape, full.surface, lo, hi))
            << name;
    }
    // Measured: 0.82 of the triangles over the five (sphere 0.75, branch
    // 0.91).
    EXPECT_LT(double(thinTriangles), 0.9 * double(fullTriangles));
}

}  // namespace dfrecon
