// The RTSTRUCT reader on real files that `make setup` generates (never
// hand-written): pydicom's phantom, and plastimatch's structure sets made
// from the ITK k-means label volume, in its native coronal orientation and
// marked axial. The independent reference for plastimatch's files is the
// label volume itself: filling each ROI's contours by the even-odd rule at
// the voxel centres must give back exactly that label's voxels.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "io/dicom/RtStruct.hpp"
#include "io/labels/LabelVolume.hpp"
#include "tests/RtStructWarnings.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

namespace {

std::string fixture(const std::string& relative) {
    const fs::path path = fs::path(DFRECON_FIXTURES) / relative;
    if (!fs::exists(path))
        ADD_FAILURE() << path << " is missing: run `make setup` (scripts/fixtures.sh makes it)";
    return path.string();
}

// plastimatch's structure sets take minutes in a sanitized binary, so
// these helpers and their tests are built for release runs only.
#ifndef DFRECON_SANITIZE_BUILD

// Crossing-number test with the half-open rule: a point flips once per
// edge whose span in y it lies in, left of the edge.
bool crossesOdd(Point2 p, const Polygon& polygon) {
    bool odd = false;
    for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
        const Point2 a = polygon[i], b = polygon[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            odd = !odd;
    }
    return odd;
}

// The voxels of `volume` whose centres the ROI's contours enclose (even-odd
// over the contours of the plane through them). Each contour visits only
// the voxels of its bounding box, so this is about linear in the contours.
std::vector<std::uint8_t> fillRoi(const Roi& roi, const VolumeGeometry& g) {
    std::vector<std::uint8_t> inside(g.voxelCount(), 0);
    for (const Slice& slice : roi.slices) {
        const auto index = g.indexOfWorld(roi.frame.toPatient({0, 0, slice.zMm}));
        const int k = int(std::lround(index[2]));
        if (k < 0 || k >= g.size[2]) continue;
        for (const Polygon& contour : slice.contours) {
            const Box2 box = boundingBox(contour);
            int lo[2] = {g.size[0], g.size[1]}, hi[2] = {-1, -1};
            for (Point2 corner :
                 {box.min, box.max, Point2{box.min.x, box.max.y}, Point2{box.max.x, box.min.y}}) {
                const auto c = g.indexOfWorld(roi.frame.toPatient({corner.x, corner.y, slice.zMm}));
                for (int a = 0; a < 2; ++a) {
                    lo[a] = std::min(lo[a], int(std::floor(c[a])));
                    hi[a] = std::max(hi[a], int(std::ceil(c[a])));
                }
            }
            for (int j = std::max(0, lo[1]); j <= std::min(g.size[1] - 1, hi[1]); ++j)
                for (int i = std::max(0, lo[0]); i <= std::min(g.size[0] - 1, hi[0]); ++i) {
                    const Vec3 p = roi.frame.fromPatient(g.worldOfIndex(i, j, k));
                    if (crossesOdd({p.x, p.y}, contour)) inside[g.linearIndex(i, j, k)] ^= 1;
                }
        }
    }
    return inside;
}

void expectContoursRebuildLabels(const std::string& study, const char* orientation) {
    const RtStructLoad load = readRtStruct(fixture(study + "/rtstruct.dcm"));
    const LabelVolume labels = readLabelVolume(fixture(study + "/labels.nii.gz"));
    const VolumeGeometry& g = labels.geometry;
    ASSERT_EQ(load.contours.rois.size(), 7u);
    for (const Roi& roi : load.contours.rois) {
        ASSERT_TRUE(roi.number.has_value());
        const int label = *roi.number;  // plastimatch numbers ROIs by label value here
        EXPECT_EQ(roi.name, "label_" + std::to_string(label));
        EXPECT_STREQ(roi.frame.orientationName(), orientation);
        // Label 1 is the background class: its region reaches every image
        // edge, and plastimatch never traces the image rim, so its contours
        // bound the complement. Every other label must come back exactly.
        if (label == 1) continue;
        const std::vector<std::uint8_t> filled = fillRoi(roi, g);
        std::size_t voxels = 0, wrong = 0;
        for (int k = 0; k < g.size[2]; ++k)
            for (int j = 1; j + 1 < g.size[1]; ++j)        // edge rows: the implied closing
                for (int i = 1; i + 1 < g.size[0]; ++i) {  // edges run through their centres
                    const std::size_t v = g.linearIndex(i, j, k);
                    const bool expected = labels.labels[v] == label;
                    voxels += expected;
                    wrong += (filled[v] != 0) != expected;
                }
        EXPECT_GT(voxels, 100u) << roi.name;
        EXPECT_EQ(wrong, 0u) << roi.name << " of " << study << ": " << wrong << " of " << voxels
                             << " voxels differ";
    }
}

#endif  // DFRECON_SANITIZE_BUILD

}  // namespace

TEST(RtStructFixtures, PydicomPhantomSkipsItsPointRois) {
    const RtStructLoad load = readRtStruct(fixture("pydicom/rtstruct.dcm"));
    ASSERT_EQ(load.contours.rois.size(), 3u);
    const Roi& patient = load.contours.rois[0];
    EXPECT_EQ(patient.name, "patient");
    ASSERT_EQ(patient.slices.size(), 3u);
    for (const Slice& slice : patient.slices) {
        ASSERT_EQ(slice.contours.size(), 1u);
        EXPECT_DOUBLE_EQ(signedArea(slice.contours[0]), 400.0 * 300.0);  // oriented CCW
    }
    EXPECT_EQ(patient.slices[0].zMm, -200.0);
    EXPECT_EQ(patient.slices[2].zMm, -180.0);
    for (std::size_t r : {1u, 2u}) {
        EXPECT_TRUE(load.contours.rois[r].slices.empty());
        EXPECT_EQ(load.rois[r].contoursSkipped, 1u);
    }
    EXPECT_TRUE(anyWarning(load, "POINT"));
}

// plastimatch's 10-20 MB files take minutes under the sanitizers (CGAL and
// DCMTK instrumented): sanitizer builds leave them to the release run; the
// same code paths run sanitized in test_RtStruct.cpp and the fuzz target.
#ifndef DFRECON_SANITIZE_BUILD
TEST(RtStructFixtures, PlastimatchCoronalContoursRebuildTheLabelVolume) {
    expectContoursRebuildLabels("kmeans", "coronal");
}

TEST(RtStructFixtures, PlastimatchAxialContoursRebuildTheLabelVolume) {
    expectContoursRebuildLabels("kmeans_axial", "axial");
}

TEST(RtStructFixtures, PlastimatchStructureSetRoundTripsExactly) {
    for (const std::string study : {"kmeans", "kmeans_axial"}) {
        const RtStructLoad first = readRtStruct(fixture(study + "/rtstruct.dcm"));
        const std::string path =
            (fs::temp_directory_path() / ("dfrecon-test-rt-" + study + ".dcm")).string();
        writeRtStruct(first.contours, path);
        const RtStructLoad second = readRtStruct(path);
        fs::remove(path);
        ASSERT_EQ(first.contours.rois.size(), second.contours.rois.size());
        for (std::size_t r = 0; r < first.contours.rois.size(); ++r) {
            const Roi &a = first.contours.rois[r], &b = second.contours.rois[r];
            EXPECT_EQ(a.number, b.number);
            ASSERT_EQ(a.slices.size(), b.slices.size()) << a.name;
            for (std::size_t s = 0; s < a.slices.size(); ++s) {
                ASSERT_EQ(a.slices[s].zMm, b.slices[s].zMm) << a.name;
                ASSERT_EQ(a.slices[s].contours, b.slices[s].contours) << a.name << " slice " << s;
            }
        }
    }
}
#endif  // DFRECON_SANITIZE_BUILD
