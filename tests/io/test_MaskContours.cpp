// Label volumes → contours: analytic shapes rasterised at voxel centres and
// contoured again lie within half a pixel of the exact cross-sections; holes
// and islands survive; non-axial frames map points back onto voxel-edge
// midpoints; the k-means fixture's contour volumes track its voxel counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "contours/InputError.hpp"
#include "io/labels/MaskContours.hpp"
#include "shapes/AnalyticShapes.hpp"

namespace dfrecon {
namespace {

namespace fs = std::filesystem;

// An axial volume of 0.7 × 0.7 × 2 mm voxels round the origin, deliberately
// not centred on it, with `label` wherever `inside` holds at a voxel centre.
template <class Inside>
LabelVolume rasterise(Inside inside, std::int32_t label = 1, std::array<int, 3> size = {80, 76, 26},
                      std::array<double, 3> originMm = {-27.3, -26.1, -25.0}) {
    LabelVolume volume;
    volume.geometry.size = size;
    volume.geometry.spacingMm = {0.7, 0.7, 2.0};
    volume.geometry.originMm = originMm;
    volume.labels.assign(volume.geometry.voxelCount(), 0);
    for (int k = 0; k < size[2]; ++k)
        for (int j = 0; j < size[1]; ++j)
            for (int i = 0; i < size[0]; ++i)
                if (inside(volume.geometry.worldOfIndex(i, j, k)))
                    volume.labels[volume.geometry.linearIndex(i, j, k)] = label;
    return volume;
}

// Orientation and nesting agree with Slice's convention (nothing to fix).
void expectOrientedByNesting(const Roi& roi) {
    for (const Slice& slice : roi.slices) {
        Slice copy = slice;
        EXPECT_EQ(normaliseOrientation(copy), 0u) << "z " << slice.zMm;
    }
}

TEST(MaskContours, SphereContoursLieWithinHalfAPixelOfTheExactCircles) {
    const auto sphere = makeShape("sphere");  // radius 20 mm round the origin
    const LabelVolume volume = rasterise([&](Vec3 p) { return sphere->signedDistance(p) < 0; });
    const ContourSet set = contoursFromLabels(volume);
    ASSERT_EQ(set.rois.size(), 1u);
    const Roi& roi = set.rois[0];
    EXPECT_EQ(roi.name, "label_1");
    EXPECT_EQ(roi.number, 1);
    EXPECT_TRUE(roi.frame.isIdentity());
    EXPECT_DOUBLE_EQ(roi.slabThicknessMm, 2.0);
    expectOrientedByNesting(roi);
    // Planes z = −25 + 2k; those strictly inside (−20, 20) hold the ball.
    EXPECT_EQ(roi.slices.size(), 20u);
    double worst = 0;
    for (const Slice& slice : roi.slices) {
        EXPECT_NEAR(std::remainder(slice.zMm + 25.0, 2.0), 0.0, 1e-12);
        const double radius = std::sqrt(400 - slice.zMm * slice.zMm);
        ASSERT_EQ(slice.contours.size(), 1u) << "z " << slice.zMm;
        EXPECT_GT(signedArea(slice.contours[0]), 0);
        for (Point2 p : slice.contours[0])
            worst = std::max(worst, std::abs(std::hypot(p.x, p.y) - radius));
    }
    EXPECT_LE(worst, 0.5 * 0.7 + 1e-9);
    EXPECT_GT(worst, 0.05) << "midpoints, not exact crossings";
}

TEST(MaskContours, TorusThroughItsHoleGivesOuterAndHole) {
    const auto torus = makeShape("torus");  // R 20, r 8, axis z
    const LabelVolume volume = rasterise([&](Vec3 p) { return torus->signedDistance(p) < 0; }, 3,
                                         {84, 82, 12}, {-29.0, -28.7, -11.0});
    MaskContourOptions options;
    options.names[3] = "Torus";
    const ContourSet set = contoursFromLabels(volume, options);
    ASSERT_EQ(set.rois.size(), 1u);
    const Roi& roi = set.rois[0];
    EXPECT_EQ(roi.name, "Torus");
    EXPECT_EQ(roi.number, 3);
    expectOrientedByNesting(roi);
    bool sawMiddle = false;
    for (const Slice& slice : roi.slices) {
        const double half = std::sqrt(64 - slice.zMm * slice.zMm);
        ASSERT_EQ(slice.contours.size(), 2u) << "z " << slice.zMm;
        const std::vector<int> depths = nestingDepths(slice);
        EXPECT_EQ(depths[0] + depths[1], 1);
        for (const Polygon& contour : slice.contours)
            for (Point2 p : contour) {
                const double rho = std::hypot(p.x, p.y);
                EXPECT_LE(std::min(std::abs(rho - (20 + half)), std::abs(rho - (20 - half))),
                          0.35 + 1e-9);
            }
        sawMiddle |= slice.zMm == 1.0 || slice.zMm == -1.0;
    }
    EXPECT_TRUE(sawMiddle);
}

TEST(MaskContours, TwoBlobsGiveTwoOuterContoursAndLabelsGiveRois) {
    const auto blobs = makeShape("two-blobs");  // balls at x = −18 (r 12) and 18 (r 9)
    LabelVolume volume = rasterise([&](Vec3 p) { return blobs->signedDistance(p) < 0; }, 5,
                                   {100, 40, 14}, {-33.2, -14.1, -13.0});
    // A second label (a 3 × 3 × 1 block) makes a second ROI.
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            volume.labels[volume.geometry.linearIndex(48 + i, 2 + j, 0)] = 2;
    const ContourSet set = contoursFromLabels(volume);
    ASSERT_EQ(set.rois.size(), 2u);
    EXPECT_EQ(set.rois[0].name, "label_2");
    ASSERT_EQ(set.rois[0].slices.size(), 1u);
    EXPECT_DOUBLE_EQ(set.rois[0].slices[0].zMm, -13.0);
    // 9 squares of 0.49 mm² less four corner triangles of 0.35²/2.
    EXPECT_NEAR(signedArea(set.rois[0].slices[0].contours[0]), 9 * 0.49 - 2 * 0.35 * 0.35, 1e-9);
    const Roi& roi = set.rois[1];
    EXPECT_EQ(roi.name, "label_5");
    expectOrientedByNesting(roi);
    const Slice* middle = nullptr;
    for (const Slice& slice : roi.slices)
        if (slice.zMm == 1.0) middle = &slice;
    ASSERT_NE(middle, nullptr);
    ASSERT_EQ(middle->contours.size(), 2u);
    for (const Polygon& contour : middle->contours) EXPECT_GT(signedArea(contour), 0);
    EXPECT_EQ(nestingDepths(*middle), (std::vector<int>{0, 0}));
}

// Every contour point, taken to patient space by the ROI's frame and back to
// a fractional voxel index, is the midpoint of a lattice edge between a
// voxel of the label and one outside it, on its own plane.
void expectPointsOnVoxelEdgeMidpoints(const LabelVolume& volume, const Roi& roi,
                                      std::int32_t label) {
    const VolumeGeometry& g = volume.geometry;
    auto labelAt = [&](long i, long j, long k) {
        if (i < 0 || j < 0 || i >= g.size[0] || j >= g.size[1]) return std::int32_t(0);
        return volume.labels[g.linearIndex(int(i), int(j), int(k))];
    };
    std::size_t checked = 0;
    for (const Slice& slice : roi.slices)
        for (const Polygon& contour : slice.contours)
            for (Point2 p : contour) {
                const auto index = g.indexOfWorld(roi.frame.toPatient({p.x, p.y, slice.zMm}));
                const long k = std::lround(index[2]);
                ASSERT_NEAR(index[2], double(k), 1e-9);
                const double fi = index[0] - std::floor(index[0]);
                const double fj = index[1] - std::floor(index[1]);
                const bool alongI = std::abs(fi - 0.5) < 1e-9;
                ASSERT_TRUE(alongI ? std::abs(fj) < 1e-9 || std::abs(fj - 1) < 1e-9
                                   : std::abs(fi) < 1e-9 || std::abs(fi - 1) < 1e-9)
                    << index[0] << ", " << index[1];
                const long i0 = alongI ? long(std::floor(index[0])) : std::lround(index[0]);
                const long j0 = alongI ? std::lround(index[1]) : long(std::floor(index[1]));
                const bool a = labelAt(i0, j0, k) == label;
                const bool b = labelAt(alongI ? i0 + 1 : i0, alongI ? j0 : j0 + 1, k) == label;
                EXPECT_NE(a, b) << index[0] << ", " << index[1] << ", " << index[2];
                ++checked;
            }
    EXPECT_GT(checked, 100u);
}

LabelVolume ballVolume(const std::array<std::array<double, 3>, 3>& direction) {
    LabelVolume volume;
    VolumeGeometry& g = volume.geometry;
    g.size = {30, 20, 24};
    g.spacingMm = {0.8, 1.5, 1.1};
    g.originMm = {-12.0, 7.0, 3.0};
    g.direction = direction;
    volume.labels.assign(g.voxelCount(), 0);
    const Vec3 centre = g.worldOfIndex(14.3, 9.6, 11.2);
    for (int k = 0; k < g.size[2]; ++k)
        for (int j = 0; j < g.size[1]; ++j)
            for (int i = 0; i < g.size[0]; ++i) {
                const Vec3 d = g.worldOfIndex(i, j, k) - centre;
                if (length(d) < 9.0) volume.labels[g.linearIndex(i, j, k)] = 7;
            }
    return volume;
}

TEST(MaskContours, CoronalVolumeFrameMapsPointsBackOntoVoxelEdgeMidpoints) {
    // Axis 0 along x, axis 1 down (−z), axis 2 along y: right-handed.
    const LabelVolume volume = ballVolume({{{{1, 0, 0}}, {{0, 0, -1}}, {{0, 1, 0}}}});
    const ContourSet set = contoursFromLabels(volume);
    ASSERT_EQ(set.rois.size(), 1u);
    const Roi& roi = set.rois[0];
    EXPECT_EQ(roi.frame.n, (Vec3{0, 1, 0}));
    EXPECT_STREQ(roi.frame.orientationName(), "coronal");
    expectOrientedByNesting(roi);
    expectPointsOnVoxelEdgeMidpoints(volume, roi, 7);
}

TEST(MaskContours, LeftHandedAxesGetTheCanonicalFrameAndKeepSlicesIncreasing) {
    // Axis 0 along x, axis 1 up (+z), axis 2 along y: x × z = −y, so the
    // volume's own frame would have n = −y; the canonical coronal one is
    // (z, x, y).
    const LabelVolume volume = ballVolume({{{{1, 0, 0}}, {{0, 0, 1}}, {{0, 1, 0}}}});
    const ContourSet set = contoursFromLabels(volume);
    ASSERT_EQ(set.rois.size(), 1u);
    const Roi& roi = set.rois[0];
    EXPECT_EQ(roi.frame.u, (Vec3{0, 0, 1}));
    EXPECT_EQ(roi.frame.v, (Vec3{1, 0, 0}));
    EXPECT_EQ(roi.frame.n, (Vec3{0, 1, 0}));
    for (std::size_t s = 1; s < roi.slices.size(); ++s)
        EXPECT_LT(roi.slices[s - 1].zMm, roi.slices[s].zMm);
    expectOrientedByNesting(roi);
    expectPointsOnVoxelEdgeMidpoints(volume, roi, 7);
}

// RAS volumes (NIfTI's usual axes, x and y negated in LPS) and volumes
// stored feet first are still axial stacks: the identity frame, so contour
// coordinates are patient LPS and every output needs no frame at all.
TEST(MaskContours, AxialVolumesInAnyAxisDirectionGetTheIdentityFrame) {
    for (const auto& direction :
         {std::array<std::array<double, 3>, 3>{{{{-1, 0, 0}}, {{0, -1, 0}}, {{0, 0, 1}}}},
          std::array<std::array<double, 3>, 3>{{{{1, 0, 0}}, {{0, -1, 0}}, {{0, 0, -1}}}},
          std::array<std::array<double, 3>, 3>{{{{0, 1, 0}}, {{1, 0, 0}}, {{0, 0, -1}}}}}) {
        const LabelVolume volume = ballVolume(direction);
        const ContourSet set = contoursFromLabels(volume);
        ASSERT_EQ(set.rois.size(), 1u);
        const Roi& roi = set.rois[0];
        EXPECT_TRUE(roi.frame.isIdentity());
        for (std::size_t s = 1; s < roi.slices.size(); ++s)
            EXPECT_LT(roi.slices[s - 1].zMm, roi.slices[s].zMm);
        expectOrientedByNesting(roi);
        expectPointsOnVoxelEdgeMidpoints(volume, roi, 7);
    }
}

TEST(MaskContours, ShearedVolumesAndBadPlanePositionsAreRefused) {
    const double c = std::sqrt(0.5);
    LabelVolume sheared = ballVolume({{{{1, 0, 0}}, {{c, c, 0}}, {{0, 0, 1}}}});
    EXPECT_THROW(contoursFromLabels(sheared), InputError);
    LabelVolume volume = ballVolume({{{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}});
    MaskContourOptions options;
    options.planePositionsMm.assign(24, 1.0);
    EXPECT_THROW(contoursFromLabels(volume, options), InputError);
    options.planePositionsMm.resize(3);
    EXPECT_THROW(contoursFromLabels(volume, options), InputError);
    volume.labels.pop_back();
    EXPECT_THROW(contoursFromLabels(volume), InputError);
}

// The generated k-means fixture (scripts/fixtures.sh): 2 × 2 × 3 mm voxels.
// Midpoint contours cut every convex pixel corner, so each label's contour
// volume falls a little short of its voxel volume.
TEST(MaskContours, KmeansFixtureContourVolumesTrackVoxelVolumes) {
    const std::string path = std::string(DFRECON_FIXTURES) + "/kmeans_axial/labels.nii.gz";
    if (!fs::exists(path)) GTEST_SKIP() << "no fixture " << path << " (scripts/setup.sh)";
    const LabelVolume volume = readLabelVolume(path);
    const VolumeGeometry& g = volume.geometry;
    const double voxelMm3 = g.spacingMm[0] * g.spacingMm[1] * g.spacingMm[2];
    const ContourSet set = contoursFromLabels(volume);
    for (std::int32_t label = 2; label <= 6; ++label) {
        const Roi* roi = set.findRoiNumber(label);
        ASSERT_NE(roi, nullptr) << label;
        expectOrientedByNesting(*roi);
        double areaMm2 = 0;
        for (const Slice& slice : roi->slices)
            for (const Polygon& contour : slice.contours) areaMm2 += signedArea(contour);
        const auto voxels = std::count(volume.labels.begin(), volume.labels.end(), label);
        const double ratio = areaMm2 * g.spacingMm[2] / (double(voxels) * voxelMm3);
        std::cout << "label " << label << ": " << voxels << " voxels, contour/voxel volume "
                  << ratio << "\n";
        RecordProperty("ratio_label_" + std::to_string(label), std::to_string(ratio));
        EXPECT_GT(ratio, 0.85);
        EXPECT_LT(ratio, 1.0);
    }
}

}  // namespace
}  // namespace dfrecon
