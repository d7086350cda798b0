// Planes left empty inside an ROI: where it ends and starts again, and the
// volume planning systems count for it (hand-computed sums).
#include <gtest/gtest.h>

#include "contours/PlaneGaps.hpp"
#include "tests/SquareStacks.hpp"

using namespace dfrecon;

namespace {

// Shorter names for the stacks these tests build.
Roi squares(const std::string& name, const std::vector<double>& z) {
    return dfrecon::testing::squareStack(name, z);
}
using dfrecon::testing::planesFrom;

}  // namespace

TEST(PlaneGaps, AnRoiWithPlanesLeftEmptyEndsAndStartsAgain) {
    ContourSet set;
    set.rois = {squares("Body", planesFrom(0, 20, 2)), squares("Gapped", {0, 2, 4, 10, 12}),
                squares("Lone", {0, 2, 4, 12})};
    findPlaneGaps(set);
    EXPECT_TRUE(set.rois[0].restartsAt.empty());
    EXPECT_EQ(set.rois[1].restartsAt, std::vector<std::size_t>{3});
    EXPECT_EQ(set.rois[2].restartsAt, std::vector<std::size_t>{3});
    EXPECT_DOUBLE_EQ(set.rois[1].imagePlaneSpacingMm, 2);
    // Runs 0–4 (2 + 2 + 2 mm) and 10–12 (2 + 2 mm); planes 6 and 8 count nothing.
    EXPECT_DOUBLE_EQ(contourVolumeMm3(set.rois[1]), 100 * (6 + 4));
    // A plane alone in its run stands for the image planes' spacing.
    EXPECT_DOUBLE_EQ(contourVolumeMm3(set.rois[2]), 100 * (6 + 2));
    const std::vector<Roi> runs = planeRuns(set.rois[1]);
    ASSERT_EQ(runs.size(), 2u);
    EXPECT_EQ(runs[0].slices.size(), 3u);
    EXPECT_EQ(runs[1].slices.front().zMm, 10);
    EXPECT_TRUE(runs[1].restartsAt.empty());
    EXPECT_EQ(runs[1].name, "Gapped");
}

TEST(PlaneGaps, SparseDrawingsAndInterleavedSeriesAreNotCut) {
    ContourSet set;
    // Every other plane of its own, all the way: a sparse drawing, not a gap.
    // Planes between another series' planes: no plane of its own is left out.
    set.rois = {squares("Body", planesFrom(0, 20, 2)), squares("Sparse", planesFrom(0, 16, 4)),
                squares("Other series", planesFrom(1, 19, 2))};
    findPlaneGaps(set);
    for (const Roi& roi : set.rois) EXPECT_TRUE(roi.restartsAt.empty()) << roi.name;
    // Without the gaps the volume is today's rule: each plane the mean of its gaps.
    EXPECT_DOUBLE_EQ(contourVolumeMm3(set.rois[1]), 100 * 4 * 5);
}

TEST(PlaneGaps, OnlyPlanesOfTheSameStackCount) {
    ContourSet set;
    set.rois = {squares("Axial", {0, 2, 4, 6, 8}), squares("Gapped", {0, 8}),
                squares("Sagittal", planesFrom(0, 8, 1))};
    set.rois[2].frame = PlaneFrame{{0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    findPlaneGaps(set);
    EXPECT_EQ(set.rois[1].restartsAt, std::vector<std::size_t>{1});  // 2, 4 and 6 left empty
    EXPECT_TRUE(set.rois[2].restartsAt.empty());
    EXPECT_DOUBLE_EQ(set.rois[2].imagePlaneSpacingMm, 1);
}

TEST(PlaneGaps, TurningAStackOverKeepsItsRuns) {
    // Planes 0, 1, 2 | 6, 7 seen along the opposite normal are -7, -6 | -2,
    // -1, 0: the run restarts at the third plane instead of the fourth.
    Roi roi;
    for (double z : {0.0, 1.0, 2.0, 6.0, 7.0})
        roi.slices.push_back({z, {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}});
    roi.restartsAt = {3};
    const double before = contourVolumeMm3(roi);
    changeFrame(roi, PlaneFrame{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}});
    EXPECT_EQ(roi.restartsAt, std::vector<std::size_t>{2});
    EXPECT_DOUBLE_EQ(roi.slices[2].zMm, -2);
    EXPECT_NEAR(contourVolumeMm3(roi), before, 1e-12);
}
