// The analytic shapes are ground truth for everything else, so they are
// checked against independent references: dense surface samples (brute
// force nearest distance), winding-number membership, and slice integration.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shapes/AnalyticShapes.hpp"

using namespace dfrecon;

namespace {

double planimetricVolume(const ContourSet& set, double spacing) {
    double v = 0;
    for (const Slice& s : set.rois[0].slices)
        for (const Polygon& c : s.contours) v += signedArea(c) * spacing;
    return v;
}

// Points on the surface: fine sections, plus the flat faces of the Y (which
// sections never reach), built here from the Y's definition.
std::vector<Vec3> surfaceSamples(const AnalyticShape& shape) {
    std::vector<Vec3> samples;
    // Planes crowd towards both ends (z = mid - half·cos θ, θ uniform), where
    // the surface turns horizontal and evenly spaced planes would leave gaps.
    const double mid = 0.5 * (shape.zMinMm() + shape.zMaxMm());
    const double half = 0.5 * (shape.zMaxMm() - shape.zMinMm());
    const int planes = 2500;
    for (int k = 0; k < planes; ++k) {
        const double z = mid - half * std::cos(M_PI * (k + 0.5) / planes);
        for (const Polygon& c : shape.section(z, 360))
            for (Point2 p : c) samples.push_back({p.x, p.y, z});
    }
    if (shape.name() == "y") {
        const double r = 8, d = 10, L = 20, step = 0.2;
        auto in = [&](double x, double y, double cx) { return std::hypot(x - cx, y) <= r; };
        for (double x = -d - r; x <= d + r; x += step)
            for (double y = -r; y <= r; y += step) {
                const bool stem = in(x, y, 0), branch = in(x, y, -d) || in(x, y, d);
                if (stem) samples.push_back({x, y, -L});
                if (branch) samples.push_back({x, y, L});
                if (stem != branch) samples.push_back({x, y, 0});
            }
        for (double z = -L; z <= L; z += 0.2)  // circle rims at the flat faces' edges
            for (int k = 0; k < 600; ++k) {
                const double t = 2 * M_PI * k / 600;
                if (z <= 0) samples.push_back({r * std::cos(t), r * std::sin(t), z});
                if (z >= 0)
                    for (double cx : {-d, d})
                        samples.push_back({cx + r * std::cos(t), r * std::sin(t), z});
            }
    }
    return samples;
}

bool insideBySections(const AnalyticShape& shape, Vec3 p) {
    int winding = 0;
    for (Polygon c : shape.section(p.z, 2000)) {
        winding += windingNumber({p.x, p.y}, c) != 0 ? 1 : 0;
    }
    return winding % 2 == 1;  // nested contours alternate inside/outside
}

}  // namespace

class ShapeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ShapeTest, SlicedAreaTimesSpacingConvergesToExactVolume) {
    const auto shape = makeShape(GetParam());
    double previousError = INFINITY;
    for (auto [spacing, points] : {std::pair{2.0, 32}, {0.5, 128}, {0.125, 512}}) {
        SynthOptions options;
        options.spacingMm = spacing;
        options.pointsPerContour = points;
        const double error = std::abs(
            planimetricVolume(sliceShape(*shape, options), spacing) / shape->volumeMm3() - 1);
        EXPECT_LT(error, previousError) << "spacing " << spacing;
        previousError = error;
    }
    EXPECT_LT(previousError, 2e-3);
}

TEST_P(ShapeTest, SectionVerticesLieOnTheSurface) {
    const auto shape = makeShape(GetParam(), 1.3);
    for (double z = shape->zMinMm() + 0.3; z < shape->zMaxMm(); z += 1.7)
        for (const Polygon& c : shape->section(z, 50))
            for (Point2 p : c) EXPECT_NEAR(shape->signedDistance({p.x, p.y, z}), 0, 1e-9);
}

TEST_P(ShapeTest, SignedDistanceMatchesBruteForceAndMembership) {
    const auto shape = makeShape(GetParam());
    const std::vector<Vec3> samples = surfaceSamples(*shape);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> xy(-45, 45);
    std::uniform_real_distribution<double> z(shape->zMinMm() - 6, shape->zMaxMm() + 6);
    for (int trial = 0; trial < 80; ++trial) {
        const Vec3 p{xy(random) * 0.8, xy(random) * 0.5, z(random)};
        const double d = shape->signedDistance(p);
        double nearest = INFINITY;
        for (const Vec3& s : samples)
            nearest =
                std::min(nearest, std::sqrt((p.x - s.x) * (p.x - s.x) + (p.y - s.y) * (p.y - s.y) +
                                            (p.z - s.z) * (p.z - s.z)));
        // Samples lie on the surface, so none can be nearer than the true distance;
        // they are dense, so the nearest is within the sampling gap of it.
        EXPECT_LE(std::abs(d), nearest + 1e-9) << "p " << p.x << " " << p.y << " " << p.z;
        EXPECT_LE(nearest, std::abs(d) + 0.3) << "p " << p.x << " " << p.y << " " << p.z;
        if (std::abs(d) > 0.05 && p.z > shape->zMinMm() && p.z < shape->zMaxMm()) {
            EXPECT_EQ(d < 0, insideBySections(*shape, p))
                << "p " << p.x << " " << p.y << " " << p.z;
        }
        if (p.z <= shape->zMinMm() || p.z >= shape->zMaxMm()) {
            EXPECT_GT(d, -1e-12);
        }
    }
}

TEST_P(ShapeTest, SignedDistanceIsOneLipschitz) {
    const auto shape = makeShape(GetParam());
    std::mt19937 random(5);
    std::uniform_real_distribution<double> coord(-40, 40), step(-2, 2);
    for (int trial = 0; trial < 2000; ++trial) {
        const Vec3 p{coord(random), coord(random), coord(random) / 2};
        const Vec3 q{p.x + step(random), p.y + step(random), p.z + step(random)};
        const double gap = std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) +
                                     (p.z - q.z) * (p.z - q.z));
        EXPECT_LE(std::abs(shape->signedDistance(p) - shape->signedDistance(q)), gap + 1e-9);
    }
}

INSTANTIATE_TEST_SUITE_P(AllShapes, ShapeTest, ::testing::ValuesIn(shapeNames()),
                         [](const auto& testInfo) {
                             std::string name = testInfo.param;
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name;
                         });

TEST(AnalyticShapes, KnownDistancesOnTheAxes) {
    const auto sphere = makeShape("sphere");
    const auto ellipsoid = makeShape("ellipsoid");
    EXPECT_NEAR(ellipsoid->signedDistance({0, 0, 0}), -15, 1e-12);
    EXPECT_NEAR(ellipsoid->signedDistance({40, 0, 0}), 10, 1e-12);
    EXPECT_NEAR(ellipsoid->signedDistance({0, 0, 20}), 5, 1e-12);
    EXPECT_NEAR(sphere->signedDistance({0, 0, 0}), -20, 1e-12);
}

TEST(AnalyticShapes, TorusSlicesAreAnnuli) {
    const ContourSet set = sliceShape(*makeShape("torus"), {});
    for (const Slice& slice : set.rois[0].slices) {
        ASSERT_EQ(slice.contours.size(), 2u);
        EXPECT_EQ(nestingDepths(slice), (std::vector<int>{0, 1}));
    }
}

TEST(AnalyticShapes, YSplitsOneContourIntoTwo) {
    const ContourSet set = sliceShape(*makeShape("y"), {});
    const auto& slices = set.rois[0].slices;
    EXPECT_EQ(slices.front().contours.size(), 1u);
    EXPECT_EQ(slices.back().contours.size(), 2u);
}

TEST(AnalyticShapes, NoiseIsSeededAndValidated) {
    SynthOptions options;
    options.noiseMm = 0.1;
    const ContourSet a = sliceShape(*makeShape("sphere"), options);
    const ContourSet b = sliceShape(*makeShape("sphere"), options);
    EXPECT_EQ(a.rois[0].slices[3].contours[0], b.rois[0].slices[3].contours[0]);
    options.noiseMm = 5;
    options.pointsPerContour = 400;
    EXPECT_THROW(sliceShape(*makeShape("sphere"), options), std::invalid_argument);
}

TEST(AnalyticShapes, RejectsUnknownNamesAndBadOptions) {
    EXPECT_THROW(makeShape("cube"), std::invalid_argument);
    SynthOptions options;
    options.spacingMm = 0;
    EXPECT_THROW(sliceShape(*makeShape("sphere"), options), std::invalid_argument);
}

TEST_P(ShapeTest, SurfaceSamplesLieOnTheSurfaceAndCoverIt) {
    const auto shape = makeShape(GetParam());
    const std::vector<Vec3> samples = sampleSurface(*shape, 4000);
    ASSERT_GE(samples.size(), 4000u);
    for (const Vec3& p : samples) EXPECT_LT(std::abs(shape->signedDistance(p)), 1e-9);
    // Coverage: every vertex of a coarse set of sections has a sample nearby.
    for (double z = shape->zMinMm() + 0.5; z < shape->zMaxMm(); z += 1.5)
        for (const Polygon& c : shape->section(z, 24))
            for (Point2 q : c) {
                double nearest = INFINITY;
                for (const Vec3& p : samples)
                    nearest = std::min(nearest, length(p - Vec3{q.x, q.y, z}));
                EXPECT_LT(nearest, 3.0) << GetParam() << " at " << q.x << "," << q.y << "," << z;
            }
}
