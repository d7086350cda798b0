// Structure algebra against independent references: the free-point
// closest-primitive kernel against its C++ twin and brute force; the
// expression parser and the margin lowering; plane sections of analytic
// fields (vertices on the exact circle); margins and Booleans of boxes,
// whose reconstructed solids are exact boxes, against the exact distance
// to a box and exact polygon areas.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "algebra/DistanceHistograms.hpp"
#include "algebra/PlaneSections.hpp"
#include "algebra/RoiExpression.hpp"
#include "algebra/SolidField.hpp"
#include "dfrecon/Algebra.hpp"
#include "dfrecon/Field.hpp"
#include "field/ClosestPrimitives.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "shapes/MeshShapes.hpp"
#include "tests/fuzz/ExpressionOracle.hpp"

using namespace dfrecon;

namespace {

ocl::Runtime& runtime() {
    static ocl::Runtime r;
    return r;
}

// Exact signed distance to the box [lo, hi].
double boxDistance(Vec3 p, Vec3 lo, Vec3 hi) {
    const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const Vec3 q{std::abs(p.x - c.x) - h.x, std::abs(p.y - c.y) - h.y, std::abs(p.z - c.z) - h.z};
    const Vec3 outside{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
    return length(outside) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

// An ROI of square (lo.x..hi.x, lo.y..hi.y) contours on planes lo.z,
// lo.z + step, ... hi.z.
Roi boxRoi(const std::string& name, const Vec3& lo, const Vec3& hi, double step) {
    const double x0 = lo.x, x1 = hi.x, y0 = lo.y, y1 = hi.y, z0 = lo.z, z1 = hi.z;
    Roi roi;
    roi.name = name;
    for (double z = z0; z <= z1 + 1e-9; z += step)
        roi.slices.push_back({z, {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
    return roi;
}

Box3 boundsOf(const TriangleSoup& soup) {
    Box3 b;
    for (const Vec3& p : soup.points) b.add(p);
    return b;
}

}  // namespace

TEST(FreePointDistances, KernelAgreesWithReferenceAndBruteForce) {
    std::vector<TriangleSoup> objects{geodesicSphere(6, 8.0, {0, 0, 0}),
                                      boxMesh({12, -5, -5}, {22, 5, 5}, 3)};
    const SurfaceScene scene(objects);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-15, 30);
    std::vector<Vec3> points;
    for (int k = 0; k < 3000; ++k)
        points.push_back({coordinate(random), coordinate(random) * 0.6, coordinate(random) * 0.6});
    std::vector<SurfaceSample> free;
    for (const Vec3& p : points) free.push_back({p, UINT32_MAX, 0});
    ClosestPrimitiveKernel kernel(runtime(), scene);
    for (int target : {-1, 0, 1}) {
        DistanceQuery query;
        query.target = target;
        const auto device = kernel.runAt(points, query);
        const auto reference = closestPrimitivesAtReference(scene, points, query);
        const auto brute = closestPrimitivesBruteForce(scene, free, query);
        for (std::size_t k = 0; k < points.size(); ++k) {
            ASSERT_NEAR(device[k].distanceMm, reference[k].distanceMm, kernel.toleranceMm() + 1e-9);
            ASSERT_NEAR(reference[k].distanceMm, brute[k].distanceMm, 1e-9);
        }
        if (target == 1) {  // the box is exact: its analytic distance
            for (std::size_t k = 0; k < points.size(); ++k)
                ASSERT_NEAR(reference[k].distanceMm,
                            boxDistance(points[k], {12, -5, -5}, {22, 5, 5}), 1e-9);
        }
    }
}

TEST(RoiExpression, ParsesMarginsBooleansAndNamesWithOperators) {
    const std::vector<std::string> names{"PTV", "PTV-70", "Rectum", "Lung L", "CTV"};
    const RoiExpression ring = parseRoiExpression("Ring = (PTV + 20) - (PTV + 3)", names);
    EXPECT_EQ(ring.name, "Ring");
    EXPECT_EQ(ring.text(), "(('PTV' + 20 mm) - ('PTV' + 3 mm))");
    EXPECT_EQ(ring.rois(), std::vector<std::string>{"PTV"});
    // The longest name wins: PTV-70 is an ROI, not PTV shrunk by 70.
    EXPECT_EQ(parseRoiExpression("E = PTV-70 - Rectum", names).text(), "('PTV-70' - 'Rectum')");
    EXPECT_EQ(parseRoiExpression("E = 'Lung L' | CTV & PTV ^ Rectum", names).text(),
              "(('Lung L' | ('CTV' & 'PTV')) ^ 'Rectum')");
    EXPECT_EQ(parseRoiExpression("E = CTV + [5,5,7,7,10,10]", names).text(),
              "('CTV' + [R 5, L 5, A 7, P 7, S 10, I 10] mm)");
    EXPECT_EQ(parseRoiExpression("E = CTV - 3mm + Rectum", names).text(),
              "(('CTV' - 3 mm) | 'Rectum')");
    const auto fails = [&](const std::string& text, const std::string& part) {
        try {
            parseRoiExpression(text, names);
            ADD_FAILURE() << text << " parsed";
        } catch (const ExpressionError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    fails("PTV + 3", "NAME = EXPRESSION");
    fails("E = PTVX", "no ROI named 'PTVX'");
    fails("E = Rectom", "'Rectum'");
    fails("E = (PTV + 3", "expected ')'");
    fails("E = PTV + 300", "beyond the 200 mm");
    fails("E = PTV + [5,5,5]", "expected ','");
    fails("E = PTV )", "unexpected ')'");
    fails(" = PTV", "no name");
}

TEST(RoiExpression, MarginsMoveOntoRoisOnlyWhereExact) {
    const std::vector<std::string> names{"A", "B"};
    const auto lowered = [&](const std::string& e) {
        return marginsOnRois(parseRoiExpression("X = " + e, names)).text();
    };
    EXPECT_EQ(lowered("(A | B) + 5"), "(('A' + 5 mm) | ('B' + 5 mm))");
    EXPECT_EQ(lowered("(A & B) - 2"), "(('A' - 2 mm) & ('B' - 2 mm))");
    EXPECT_EQ(lowered("(A + 2) + 3"), "('A' + 5 mm)");
    EXPECT_EQ(lowered("(A - 2) - 3"), "('A' - 5 mm)");
    for (const char* refused :
         {"(A - B) + 5", "(A & B) + 5", "(A | B) - 5", "(A + 2) - 1", "(A ^ B) + 1"})
        EXPECT_THROW(lowered(refused), ExpressionError) << refused;
}

TEST(PlaneSections, VerticesLieOnTheExactBoundary) {
    // A disc of radius 7 with a hole of radius 3 around (1, 2), per plane
    // radius shrinking with |z| (a 1-Lipschitz field in the plane).
    const PlaneField annulus = [](const std::vector<Vec3>& points) {
        std::vector<double> f;
        for (const Vec3& p : points) {
            const double r = std::hypot(p.x - 1, p.y - 2);
            f.push_back(std::max(r - (7 - std::abs(p.z)), 3 - r));
        }
        return f;
    };
    PlaneSectionStats stats;
    const std::vector<Slice> slices =
        planeSections(annulus, {-5, 0, 2, 3.5, 6}, {-8, 10, -7, 11}, {}, &stats);
    ASSERT_EQ(slices.size(), 3u);  // at |z| ≥ 4 the disc is inside the hole
    for (const Slice& s : slices) {
        ASSERT_EQ(s.contours.size(), 2u) << s.zMm;
        double area = 0;
        for (const Polygon& p : s.contours) {
            area += signedArea(p);
            for (const Point2& v : p) {
                const double r = std::hypot(v.x - 1, v.y - 2);
                // On the circle, or 5 % of a step off a lattice sample.
                EXPECT_LT(std::min(std::abs(r - (7 - std::abs(s.zMm))), std::abs(r - 3)),
                          0.05 * 0.25);
            }
        }
        const double outer = 7 - std::abs(s.zMm);
        const double exact = M_PI * (outer * outer - 9);
        // Chords of a 0.25 mm lattice: relative error under step²/(8 r) · 2/r.
        EXPECT_NEAR(area, exact, 0.003 * exact) << s.zMm;
    }
    // Only cells near the boundary were sampled finely.
    EXPECT_LT(stats.fineSamples, 5 * std::size_t(72 * 72));
}

TEST(StructureAlgebra, MarginOfABoxIsItsExactOffsetOnEveryPlane) {
    ContourSet set;
    set.rois.push_back(boxRoi("Box", {-10, -6, 0}, {10, 6, 20}, 2.5));
    StructureAlgebraOptions options;
    for (DistanceBackend backend : {DistanceBackend::Device, DistanceBackend::Reference}) {
        options.backend = backend;
        for (double margin : {5.0, -3.0}) {
            const StructureAlgebraResult r =
                marginRoi(runtime(), set, "Box", DirectionalMargin::uniform(margin), "M", options);
            // The reconstructed box is the exact box between its lids.
            const RoiSurface solid = reconstructRoi(runtime(), set.rois[0]);
            const Box3 box = boundsOf(solid.surface);
            EXPECT_NEAR(box.lo.x, -10, 1e-5);
            std::size_t vertices = 0, onBoundary = 0;
            for (const Slice& s : r.roi.slices)
                for (const Polygon& p : s.contours)
                    for (const Point2& v : p) {
                        // Exact, or kept 5 % of a step off a lattice sample.
                        const double off =
                            std::abs(boxDistance({v.x, v.y, s.zMm}, box.lo, box.hi) - margin);
                        ASSERT_LT(off, 0.05 * options.sections.stepMm)
                            << v.x << " " << v.y << " " << s.zMm;
                        onBoundary += off < 1e-4;  // the 0.1 µm grid
                        ++vertices;
                    }
            EXPECT_GT(vertices, 100u);
            // The rest lie where the boundary passes near a sample (10 % of each edge).
            EXPECT_GT(double(onBoundary), 0.8 * double(vertices));
            // Planes continue at 2.5 mm as far as the growth reaches.
            const double zTop = r.roi.slices.back().zMm;
            EXPECT_LE(zTop, box.hi.z + std::max(margin, 0.0));
            EXPECT_GT(zTop,
                      box.hi.z + std::max(margin, 0.0) - 2.5 - (margin < 0 ? 2.5 - margin : 0));
            // Section areas in the middle: the rounded rectangle (growth) or
            // the smaller rectangle (shrink), within the chords' error.
            for (const Slice& s : r.roi.slices) {
                if (s.zMm < box.lo.z + std::abs(margin) || s.zMm > box.hi.z - std::abs(margin))
                    continue;
                double area = 0;
                for (const Polygon& p : s.contours) area += signedArea(p);
                const double a = 20 + 2 * margin, b = 12 + 2 * margin;
                const double exact = margin > 0 ? a * b - (4 - M_PI) * margin * margin : a * b;
                // Chords of the rounded corners (4 · arc · step² / (12 r)),
                // or the shrink's four creases cut (step² / 2 each).
                const double h = options.sections.stepMm;
                const double chords = margin > 0 ? 2 * M_PI * h * h / 12 : 4 * h * h / 2;
                EXPECT_NEAR(area, exact, 1.5 * chords) << s.zMm << " margin " << margin;
            }
        }
    }
}

TEST(StructureAlgebra, APlaneOnAFlatFaceOfTheResultHoldsNoSpecks) {
    // The box's lids lie at -1.25 and 21.25 mm; grown by 3.75 mm they lie
    // on the planes -5 and 25, where the field is zero up to rounding over
    // the whole face.
    ContourSet set;
    set.rois.push_back(boxRoi("Box", {-10, -6, 0}, {10, 6, 20}, 2.5));
    const StructureAlgebraResult r =
        marginRoi(runtime(), set, "Box", DirectionalMargin::uniform(3.75), "M");
    for (const Slice& s : r.roi.slices) EXPECT_EQ(s.contours.size(), 1u) << s.zMm;
    EXPECT_GT(r.roi.slices.front().zMm, -5);
    EXPECT_LT(r.roi.slices.back().zMm, 25);
}

TEST(StructureAlgebra, BooleansOfBoxesHaveTheExactAreas) {
    ContourSet set;
    set.rois.push_back(boxRoi("A", {0, 0, 0}, {40, 40, 20}, 2));
    set.rois.push_back(boxRoi("B", {20, 10, 4}, {60, 30, 30}, 2));
    const struct {
        const char* expression;
        double area;  // on planes where both are
    } cases[] = {
        {"U = A | B", 1600 + 400}, {"I = A & B", 400}, {"D = A - B", 1200}, {"X = A ^ B", 1600}};
    for (const auto& c : cases) {
        const StructureAlgebraResult r = combineRois(runtime(), set, c.expression);
        bool checked = false;
        for (const Slice& s : r.roi.slices) {
            if (s.zMm < 6 || s.zMm > 18) continue;
            double area = 0;
            for (const Polygon& p : s.contours) area += signedArea(p);
            // Marching squares cuts the corners where the boundaries cross:
            // at most step² per corner.
            EXPECT_NEAR(area, c.area, 8 * 0.25 * 0.25) << c.expression << " z " << s.zMm;
            checked = true;
        }
        EXPECT_TRUE(checked) << c.expression;
    }
    EXPECT_THROW(combineRois(runtime(), set, "E = A & (B + 0) - A"), std::invalid_argument);
}

TEST(StructureAlgebra, EllipsoidalMarginsScaleEachAxis) {
    ContourSet set;
    set.rois.push_back(boxRoi("Box", {-10, -6, 0}, {10, 6, 20}, 2.5));
    DirectionalMargin m;
    m.mm = {4, 4, 8, 8, 0, 0};  // in the plane only: x by 4, y by 8
    const StructureAlgebraResult r = marginRoi(runtime(), set, "Box", m, "E");
    for (const Slice& s : r.roi.slices) {
        if (s.zMm < 2 || s.zMm > 18) continue;
        double xMax = -INFINITY, yMax = -INFINITY;
        for (const Polygon& p : s.contours)
            for (const Point2& v : p) {
                xMax = std::max(xMax, v.x);
                yMax = std::max(yMax, v.y);
            }
        EXPECT_NEAR(xMax, 14, 0.01);
        EXPECT_NEAR(yMax, 14, 0.01);
    }
}

TEST(StructureAlgebra, MarginsPerDirectionAreTheExactOctantSum) {
    // A box grown by the eight-octant body: p is in it when
    // sqrt(Σ (excess_i / a_i(side))²) ≤ 1, excess_i being how far p lies
    // beyond the box along axis i (a box's nearest point is per axis).
    ContourSet set;
    set.rois.push_back(boxRoi("Box", {-10, -6, 0}, {10, 6, 20}, 2.5));
    const Box3 box = boundsOf(reconstructRoi(runtime(), set.rois[0]).surface);
    const auto gaugeFromBox = [&](Vec3 p, const std::array<double, 6>& a) {
        const double ex = p.x < box.lo.x   ? (box.lo.x - p.x) / a[0]
                          : p.x > box.hi.x ? (p.x - box.hi.x) / a[1]
                                           : 0;
        const double ey = p.y < box.lo.y   ? (box.lo.y - p.y) / a[2]
                          : p.y > box.hi.y ? (p.y - box.hi.y) / a[3]
                                           : 0;
        const double ez = p.z > box.hi.z   ? (p.z - box.hi.z) / a[4]
                          : p.z < box.lo.z ? (box.lo.z - p.z) / a[5]
                                           : 0;
        return std::sqrt(ex * ex + ey * ey + ez * ez);
    };
    DirectionalMargin m;
    m.mm = {5, 3, 6, 2, 4, 1};  // R, L, A, P, S, I
    for (DistanceBackend backend : {DistanceBackend::Device, DistanceBackend::Reference}) {
        StructureAlgebraOptions options;
        options.backend = backend;
        const StructureAlgebraResult r = marginRoi(runtime(), set, "Box", m, "O", options);
        std::size_t vertices = 0;
        for (const Slice& s : r.roi.slices)
            for (const Polygon& p : s.contours)
                for (const Point2& v : p) {
                    // 1 on the boundary; 5 % of a step (over the smallest axis) near a sample.
                    ASSERT_NEAR(gaugeFromBox({v.x, v.y, s.zMm}, m.mm), 1, 0.05 * 0.25 / 1)
                        << v.x << " " << v.y << " " << s.zMm;
                    ++vertices;
                }
        EXPECT_GT(vertices, 100u);
        // Planes reach S 4 mm above the box and I 1 mm below it.
        EXPECT_LE(r.roi.slices.back().zMm, box.hi.z + 4);
        EXPECT_GE(r.roi.slices.front().zMm, box.lo.z - 1);
    }
    // Shrunk: the box's faces move in by their own values, corners stay sharp.
    m.mm = {-2, -1, -3, -1, -2, -2};
    const StructureAlgebraResult r = marginRoi(runtime(), set, "Box", m, "S");
    for (const Slice& s : r.roi.slices) {
        if (s.zMm < box.lo.z + 2.5 || s.zMm > box.hi.z - 2.5) continue;
        ASSERT_EQ(s.contours.size(), 1u);
        double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
        for (const Point2& v : s.contours[0]) {
            xMin = std::min(xMin, v.x), xMax = std::max(xMax, v.x);
            yMin = std::min(yMin, v.y), yMax = std::max(yMax, v.y);
        }
        EXPECT_NEAR(xMin, -8, 0.02);
        EXPECT_NEAR(xMax, 9, 0.02);
        EXPECT_NEAR(yMin, -3, 0.02);
        EXPECT_NEAR(yMax, 5, 0.02);
    }
}

TEST(DistanceHistograms, ConcentricSpheresFollowTheAnalyticOvh) {
    // OAR a ball of 20 mm around a target ball of 8 mm: the fraction of the
    // OAR within d of the target is ((8 + d) / 20)³ for -8 ≤ d ≤ 12.
    const TriangleSoup oar = geodesicSphere(40, 20), target = geodesicSphere(40, 8);
    DistanceHistogramOptions options;
    const DistanceHistograms h = distanceHistograms(oar, target, options, &runtime());
    EXPECT_NEAR(h.volume.total, 4.0 / 3 * M_PI * 8000, 0.005 * 4.0 / 3 * M_PI * 8000);
    for (double d : {-6.0, -2.0, 0.0, 3.0, 7.0, 11.0}) {
        const double exact = std::pow((8 + d) / 20, 3);
        EXPECT_NEAR(h.volume.fractionWithin(d), exact, 0.005) << d;
    }
    EXPECT_NEAR(h.volume.fractionWithin(0), std::pow(0.4, 3), 0.005);
    // The OAR's surface lies 12 mm from the target everywhere.
    EXPECT_EQ(h.surface.fractionWithin(11.95), 0.0);
    EXPECT_EQ(h.surface.fractionWithin(12.05), 1.0);
    EXPECT_NEAR(h.surface.total, 4 * M_PI * 400, 0.005 * 4 * M_PI * 400);
}

TEST(DistanceHistograms, AgreeWithBruteForcePointDistances) {
    // A box OAR (inside known exactly) beside a target ball; the reference
    // measures every point to every target triangle on a grid of its own.
    const Vec3 lo{-4, -10, -6}, hi{18, 10, 6};
    const TriangleSoup oar = boxMesh(lo, hi, 4), target = geodesicSphere(12, 7, {-6, 0, 0});
    DistanceHistogramOptions options;
    options.backend = DistanceBackend::Reference;
    const DistanceHistograms mine = distanceHistograms(oar, target, options, nullptr);
    options.backend = DistanceBackend::Device;
    const DistanceHistograms device = distanceHistograms(oar, target, options, &runtime());

    const double step = 0.5;
    const SurfaceScene scene({target});
    std::vector<SurfaceSample> points;
    for (double z = lo.z + step / 2; z < hi.z; z += step)
        for (double y = lo.y + step / 2; y < hi.y; y += step)
            for (double x = lo.x + step / 2; x < hi.x; x += step)
                points.push_back({{x, y, z}, UINT32_MAX, 0});
    const std::vector<ClosestPrimitive> brute = closestPrimitivesBruteForce(scene, points);
    for (double d : {-3.0, -1.0, 0.0, 2.0, 5.0, 10.0, 20.0}) {
        std::size_t within = 0;
        for (const ClosestPrimitive& c : brute) within += c.distanceMm <= d;
        const double reference = double(within) / double(brute.size());
        EXPECT_NEAR(mine.volume.fractionWithin(d), reference, 0.005) << d;
        EXPECT_NEAR(device.volume.fractionWithin(d), mine.volume.fractionWithin(d), 1e-9) << d;
    }
    EXPECT_NEAR(mine.volume.total, 22 * 20 * 12, 0.005 * 22 * 20 * 12);
}

TEST(DistanceHistograms, SpacingsThatWouldTakeTooManyCellsAreCoarsenedAndReported) {
    // A 1e-6 mm surface spacing on a 20 mm box would be some 10^15 cells;
    // with a budget of 20 000 the spacing grows until it fits, the cells
    // still cover the whole surface, and the spacing used is reported.
    const TriangleSoup oar = boxMesh({0, 0, 0}, {20, 20, 20}, 2),
                       target = geodesicSphere(6, 5, {40, 10, 10});
    DistanceHistogramOptions options;
    options.backend = DistanceBackend::Reference;
    options.volumeStepMm = 2;
    options.surfaceSpacingMm = 1e-6;
    options.maxSurfaceCells = 20000;
    const DistanceHistograms h = distanceHistograms(oar, target, options, nullptr);
    EXPECT_GT(h.surfaceSpacingMm, 1e-6);
    EXPECT_LE(h.surface.distanceMm.size(), options.maxSurfaceCells);
    EXPECT_GT(h.surface.distanceMm.size(), options.maxSurfaceCells / 4);
    EXPECT_NEAR(h.surface.total, 6 * 400, 1e-6);
    // Within the budget the asked spacing is the one used.
    options.surfaceSpacingMm = 2;
    EXPECT_EQ(distanceHistograms(oar, target, options, nullptr).surfaceSpacingMm, 2.0);
}

TEST(EuclideanDistanceVolume, IsTheExactDistanceToTheReconstructedBox) {
    const Roi roi = boxRoi("Box", {-10, -6, 0}, {10, 6, 20}, 2.5);
    RoiFieldOptions options;
    options.pixelMm = 1;
    const RoiDistanceVolume v = roiEuclideanDistanceVolume(runtime(), roi, options);
    const Box3 box = boundsOf(reconstructRoi(runtime(), roi).surface);
    const DenseDistanceVolume& d = v.volume;
    ASSERT_GT(d.nx * d.ny * d.nz, 1000);
    double worst = 0;
    for (int k = 0; k < d.nz; ++k)
        for (int j = 0; j < d.ny; ++j)
            for (int i = 0; i < d.nx; ++i) {
                const Vec3 p{d.originMm[0] + i * d.voxelMm[0], d.originMm[1] + j * d.voxelMm[1],
                             d.originMm[2] + k * d.voxelMm[2]};
                const float value = d.valuesMm[(std::size_t(k) * d.ny + j) * d.nx + i];
                worst = std::max(worst, std::abs(value - boxDistance(p, box.lo, box.hi)));
            }
    EXPECT_LT(worst, 1e-4);  // float values, exact distances
}

TEST(RoiExpressionFuzzing, EveryKeptDefinitionHoldsTheOracle) {
    // tests/data/fuzz-expression: the fuzz target's seeds and findings
    // (tests/fuzz/fuzz_roi_expression.cpp), replayed here and so under the
    // sanitizers in CI.
    namespace fs = std::filesystem;
    int files = 0;
    for (const auto& entry :
         fs::directory_iterator(fs::path(DFRECON_TEST_DATA) / "fuzz-expression")) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string definition((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
        EXPECT_TRUE(fuzzing::expressionHolds(definition)) << entry.path();
        ++files;
    }
    EXPECT_GE(files, 10);
}
