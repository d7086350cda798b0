// Slabs between runs of repeated contours: which layers repeat, and a stem
// splitting into two branches against its exact surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contours/ContourSet.hpp"
#include "geometry/MeshCheck.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/StepSlabs.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"
#include "tests/DistancesBetweenPlanes.hpp"

namespace dfrecon {
namespace {

Polygon square(double x0, double side) {
    return {{x0, 0}, {x0 + side, 0}, {x0 + side, side}, {x0, side}};
}

Polygon startingAt(const Polygon& p, std::size_t start) {
    Polygon out;
    for (std::size_t i = 0; i < p.size(); ++i) out.push_back(p[(start + i) % p.size()]);
    return out;
}

}  // namespace

TEST(StepSlabs, LayersRepeatWhenTheyHoldTheSamePointsInAnyOrderOfContours) {
    const Layer a{0, {square(0, 4), square(10, 2)}, {}};
    // The same contours listed the other way round, one started elsewhere.
    EXPECT_TRUE(sameContours(a, Layer{1, {square(10, 2), startingAt(square(0, 4), 2)}, {}}, 1e-3));
    // A point moved by more than the tolerance, a contour reversed, one
    // contour missing, a point more on the same outline: not a repeat.
    Polygon moved = square(0, 4);
    moved[1].x += 0.01;
    EXPECT_FALSE(sameContours(a, Layer{1, {moved, square(10, 2)}, {}}, 1e-3));
    EXPECT_TRUE(sameContours(a, Layer{1, {moved, square(10, 2)}, {}}, 0.02));
    Polygon backwards = square(0, 4);
    std::reverse(backwards.begin(), backwards.end());
    EXPECT_FALSE(sameContours(a, Layer{1, {backwards, square(10, 2)}, {}}, 1e-3));
    EXPECT_FALSE(sameContours(a, Layer{1, {square(0, 4)}, {}}, 1e-3));
    Polygon finer = square(0, 4);
    finer.insert(finer.begin() + 1, Point2{2, 0});
    EXPECT_FALSE(sameContours(a, Layer{1, {finer, square(10, 2)}, {}}, 1e-3));
}

TEST(StepSlabs, AStepNeedsARepeatOnBothSidesAndAChangeAcross) {
    const Layer p{0, {square(0, 4)}, {}}, q{0, {square(1, 3)}, {}};
    const std::deque<Layer> stairs{p, p, q, q};
    EXPECT_FALSE(isStepSlab(stairs, 0));  // no plane below the first
    EXPECT_TRUE(isStepSlab(stairs, 1));
    EXPECT_FALSE(isStepSlab(stairs, 2));  // no plane above the last
    const std::deque<Layer> ramp{p, p, q, Layer{0, {square(2, 2)}, {}}};
    EXPECT_FALSE(isStepSlab(ramp, 1));  // the upper side changes again above
    const std::deque<Layer> flat{p, p, p, p};
    EXPECT_FALSE(isStepSlab(flat, 1));  // nothing changes across
}

TEST(StepSlabs, AStemSplittingIntoBranchesStepsWhereTheDataSaysNothingOfASlope) {
    // y: a stem cylinder below z = 0, two branch cylinders above, the same
    // sections on every plane of each. Across the slab holding z = 0 a
    // slope cuts the step's flat faces (1 mm from the truth at 2 mm planes);
    // the step is the exact surface there, and its volume is the contours'.
    const auto shape = makeShape("y");
    SynthOptions slicing;
    slicing.spacingMm = 2;
    slicing.pointsPerContour = 96;
    const ContourSet set = sliceShape(*shape, slicing);
    const Roi& roi = set.rois[0];
    ReconstructionOptions sloped;
    sloped.stepBetweenRepeats = false;
    const Reconstruction slope = reconstructSurface(cpuRuntime(), roi, sloped);
    const Reconstruction step = reconstructSurface(cpuRuntime(), roi);
    ASSERT_TRUE(slope.check.validSolid());
    ASSERT_TRUE(step.check.validSolid());
    EXPECT_EQ(slope.stats.stepSlabs, 0u);
    EXPECT_EQ(step.stats.stepSlabs, 1u);
    auto farthestBetweenPlanes = [&](const TriangleSoup& soup) {
        const std::vector<double> d = testing::distancesBetweenPlanes(*shape, roi, soup);
        return d.empty() ? 0.0 : *std::max_element(d.begin(), d.end());
    };
    EXPECT_GT(farthestBetweenPlanes(slope.surface), 0.5);
    // The sections are 96-gons in the circles: their sag is the distance left.
    const double sagMm = 8 * (1 - std::cos(kPi / 96));
    EXPECT_LT(farthestBetweenPlanes(step.surface), sagMm + 1e-3);
    EXPECT_NEAR(step.check.volumeMm3, contourVolumeMm3(roi), 1e-3 * contourVolumeMm3(roi));
}

}  // namespace dfrecon
