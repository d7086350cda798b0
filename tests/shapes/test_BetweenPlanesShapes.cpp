// The between-planes shapes are ground truth for the between-slices
// accuracy benchmark, so their distances are checked against references that
// do not use them: points of each shape's own parametrisation (brute-force
// nearest distance, inside/outside by the nearest point's outward normal), and
// their volumes against fine slices. Fast: a few tenths of a second in all.
#include "shapes/BetweenPlanesShapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/ContourValidation.hpp"
#include "shapes/ImplicitSection.hpp"

using namespace dfrecon;

namespace {

constexpr double kStep = 0.25;  // parametric sample spacing, mm

struct Nearest {
    double distance = INFINITY;
    const SurfacePoint* point = nullptr;
};

Nearest bruteForceNearest(const std::vector<SurfacePoint>& samples, Vec3 p) {
    Nearest best;
    for (const SurfacePoint& s : samples) {
        const double d = length(p - s.point);
        if (d < best.distance) best = {d, &s};
    }
    return best;
}

// Query points: mostly near the surface (where a benchmark asks), some far.
std::vector<Vec3> queries(const AnalyticShape& shape, const std::vector<SurfacePoint>& samples,
                          int count, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::size_t> pick(0, samples.size() - 1);
    std::uniform_real_distribution<double> offset(-3, 3), unit(-1, 1);
    std::vector<Vec3> points;
    for (int i = 0; i < count; ++i) {
        const SurfacePoint& s = samples[pick(random)];
        const Vec3 jitter{unit(random), unit(random), unit(random)};
        points.push_back(s.point + offset(random) * s.normal + 0.5 * jitter);
    }
    for (int i = 0; i < count / 4; ++i) {
        const double span = shape.zMaxMm() - shape.zMinMm();
        points.push_back({30 * unit(random), 30 * unit(random),
                          0.5 * (shape.zMinMm() + shape.zMaxMm()) + span * unit(random)});
    }
    return points;
}

std::vector<std::string> exactShapeNames() {
    std::vector<std::string> names;
    for (const std::string& name : betweenPlanesShapeNames())
        if (makeBetweenPlanesShape(name, 1.0)->distanceIsExact()) names.push_back(name);
    return names;
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

}  // namespace

class BetweenPlanesShape : public ::testing::TestWithParam<std::string> {};
class ExactBetweenPlanesShape : public ::testing::TestWithParam<std::string> {};

TEST_P(ExactBetweenPlanesShape, SignedDistanceMatchesItsParametrisation) {
    const auto shape = makeBetweenPlanesShape(GetParam(), 1.0);
    const std::vector<SurfacePoint> samples = shape->parametricSurface(kStep);
    ASSERT_GT(samples.size(), 1000u);
    for (const SurfacePoint& s : samples) {
        ASSERT_NEAR(shape->signedDistance(s.point), 0, 1e-9);
        ASSERT_NEAR(length(s.normal), 1, 1e-9);
    }
    for (const Vec3& p : queries(*shape, samples, 40, 3)) {
        const double d = shape->signedDistance(p);
        const Nearest nearest = bruteForceNearest(samples, p);
        // Samples lie on the surface, so none is nearer than the true
        // distance; they are dense, so the nearest is within the gap of it.
        EXPECT_LE(std::abs(d), nearest.distance + 1e-9) << p.x << " " << p.y << " " << p.z;
        EXPECT_LE(nearest.distance, std::abs(d) + kStep) << p.x << " " << p.y << " " << p.z;
        // Inside exactly when p lies behind the nearest point's outward normal.
        if (std::abs(d) > 2 * kStep) {
            EXPECT_EQ(d < 0, dot(p - nearest.point->point, nearest.point->normal) < 0)
                << p.x << " " << p.y << " " << p.z;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Exact, ExactBetweenPlanesShape, ::testing::ValuesIn(exactShapeNames()),
                         testName);

TEST_P(BetweenPlanesShape, DistanceIsOneLipschitzAndZRangeIsTight) {
    const auto shape = makeBetweenPlanesShape(GetParam(), 1.0);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> coord(-35, 35), step(-2, 2);
    for (int trial = 0; trial < 500; ++trial) {
        const Vec3 p{coord(random), coord(random), coord(random)};
        const Vec3 q{p.x + step(random), p.y + step(random), p.z + step(random)};
        EXPECT_LE(std::abs(shape->signedDistance(p) - shape->signedDistance(q)),
                  length(p - q) + 1e-9);
    }
    // Something just inside each end of the z range, nothing just beyond.
    auto traced = [&](double z) {
        Box2 region{{-60, -60}, {60, 60}};
        return implicitSection([&](Vec3 p) { return shape->signedDistance(p); }, region, z, 0.02,
                               16);
    };
    EXPECT_FALSE(traced(shape->zMinMm() + 0.01).empty());
    EXPECT_FALSE(traced(shape->zMaxMm() - 0.01).empty());
    EXPECT_TRUE(traced(shape->zMinMm() - 0.01).empty());
    EXPECT_TRUE(traced(shape->zMaxMm() + 0.01).empty());
}

TEST_P(BetweenPlanesShape, SectionsAreValidContoursOnTheSurface) {
    const auto shape = makeBetweenPlanesShape(GetParam(), 1.0);
    SynthOptions options;
    options.spacingMm = 5;
    options.pointsPerContour = 128;
    const ContourSet set = sliceShape(*shape, options);
    ASSERT_FALSE(set.rois[0].slices.empty());
    for (const Slice& slice : set.rois[0].slices) {
        EXPECT_FALSE(findContourDefect(slice.contours)) << "z " << slice.zMm;
        for (const Polygon& c : slice.contours) {
            EXPECT_GE(c.size(), 16u);
            for (Point2 p : c) ASSERT_NEAR(shape->signedDistance({p.x, p.y, slice.zMm}), 0, 1e-9);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(All, BetweenPlanesShape, ::testing::ValuesIn(betweenPlanesShapeNames()),
                         testName);

TEST(BetweenPlanesShapes, ClosedFormVolumesMatchIntegratedSections) {
    // Pappus, Steiner, spherical caps and the waist's integral against the
    // midpoint rule over traced sections every 0.5 mm: within 1.2e-3 for the
    // plate (its area changes slope where planes leave its flat faces) and
    // 2e-4 for the others at scale 1, and all within 1.4e-4 at 0.1 mm
    // (measured); the tube and the neck are checked at half size, where
    // 0.5 mm is twice as coarse (about 6e-4), to stay fast. The smallest term
    // checked, the plate's corners, is 3.7e-3 of its volume. Tori, capsules
    // and the ellipsoid have textbook volumes.
    for (const auto& [name, scale] :
         {std::pair{"bent-tube", 0.5}, {"plate-20", 1.0}, {"neck", 0.5}}) {
        const auto shape = makeBetweenPlanesShape(name, scale);
        const double integrated = sectionedVolume([&](Vec3 p) { return shape->signedDistance(p); },
                                                  Box2{{-60, -60}, {60, 60}}, shape->zMinMm(),
                                                  shape->zMaxMm(), 0.5, 0.25);
        EXPECT_NEAR(integrated / shape->volumeMm3(), 1, 2e-3) << name;
    }
}

TEST(BetweenPlanesShapes, SectionsSplitWhereTheGeometrySays) {
    // A plane through a torus's centre at more than asin(r/R) to its own
    // plane cuts two separate discs; the branch has one stem and two tips.
    for (const char* name : {"torus-30", "torus-60"}) {
        const auto torus = makeBetweenPlanesShape(name, 1.0);
        EXPECT_EQ(torus->section(0, 64).size(), 2u) << name;
    }
    const auto branch = makeBetweenPlanesShape("branch", 1.0);
    EXPECT_EQ(branch->section(branch->zMinMm() + 3, 64).size(), 1u);
    EXPECT_EQ(branch->section(branch->zMaxMm() - 5, 64).size(), 2u);
    // The thin plate is thinner than 5 mm yet cut by three planes at 5 mm.
    SynthOptions options;
    options.spacingMm = 5;
    EXPECT_EQ(sliceShape(*makeBetweenPlanesShape("plate-20", 1.0), options).rois[0].slices.size(),
              3u);
}

TEST(BetweenPlanesShapes, BranchIsABoundedSmoothUnion) {
    const auto branch = makeBetweenPlanesShape("branch", 1.0);
    EXPECT_FALSE(branch->distanceIsExact());
    // Away from the blend it is the capsules' exact distance: those surface
    // points are exactly on the zero set, and the value never exceeds the
    // distance to them.
    const std::vector<SurfacePoint> samples = branch->parametricSurface(kStep);
    ASSERT_GT(samples.size(), 1000u);
    std::mt19937 random(9);
    std::uniform_real_distribution<double> coord(-30, 30);
    for (int trial = 0; trial < 80; ++trial) {
        const Vec3 p{coord(random), coord(random), coord(random)};
        EXPECT_LE(std::abs(branch->signedDistance(p)),
                  bruteForceNearest(samples, p).distance + 1e-9);
    }
    // Its volume is sectionedVolume's integral, checked on the exact shapes
    // above (and too slow to compute here).
}

TEST(BetweenPlanesShapes, NamesAreKnownToMakeShape) {
    for (const std::string& name : betweenPlanesShapeNames()) {
        EXPECT_EQ(makeShape(name)->name(), name);
        EXPECT_FALSE(shapeDescription(name).empty());
        EXPECT_NE(std::find(allShapeNames().begin(), allShapeNames().end(), name),
                  allShapeNames().end());
        EXPECT_EQ(std::find(shapeNames().begin(), shapeNames().end(), name), shapeNames().end());
    }
    EXPECT_EQ(makeBetweenPlanesShape("sphere", 1.0), nullptr);
    const auto big = makeBetweenPlanesShape("neck", 2.0), small = makeBetweenPlanesShape("neck", 1);
    EXPECT_NEAR(big->volumeMm3(), 8 * small->volumeMm3(), 1e-6 * big->volumeMm3());
    EXPECT_NEAR(big->signedDistance({1, 2, 3}), 2 * small->signedDistance({0.5, 1, 1.5}), 1e-12);
}
