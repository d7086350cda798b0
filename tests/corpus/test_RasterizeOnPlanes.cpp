// Label maps exact on the contour planes: every voxel centre on a plane is
// inside exactly when it is inside that plane's contours, checked against
// the winding numbers at each centre (brute force), whatever the field's
// pixel size, from the reconstructed solid (rasterize's default) and from
// the 3D field; planes left empty inside an ROI fill nothing; a label map
// from the solid has the surface's volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "contours/PlaneGaps.hpp"
#include "dfrecon/Field.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "field/Rasterization.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

// Wobbly outlines with a hole: many centres lie within micrometres of an
// edge on a fine grid.
Roi wobblyRoi(std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> wobble(-0.8, 0.8);
    Roi roi;
    roi.name = "Heart";
    for (double z : {0.0, 2.0, 4.0, 6.0}) {
        Polygon outer, hole;
        for (int k = 0; k < 90; ++k) {
            const double t = 2 * 3.14159265358979 * k / 90;
            const double r = 20 + wobble(random);
            outer.push_back({r * std::cos(t), 0.8 * r * std::sin(t)});
        }
        for (int k = 0; k < 30; ++k) {
            const double t = -2 * 3.14159265358979 * k / 30;
            hole.push_back({4 + 5 * std::cos(t) + 0.1 * wobble(random), 5 * std::sin(t)});
        }
        roi.slices.push_back({z, {outer, hole}});
    }
    return roi;
}

// The even-odd rule at p: an odd number of crossings to its right, by the
// exact side test at each edge.
bool insideByWinding(const Slice& slice, Point2 p) {
    int crossed = 0;
    for (const Polygon& c : slice.contours)
        for (std::size_t k = 0; k < c.size(); ++k)
            crossed += windingCrossing(p, c[k], c[(k + 1) % c.size()]) != 0;
    return crossed % 2 == 1;
}

TEST(RasterizeOnPlanes, EveryCentreOnAPlaneIsTheContoursInside) {
    for (std::uint32_t seed = 0; seed < 3; ++seed) {
        const Roi roi = wobblyRoi(seed);
        VolumeGeometry grid;
        grid.size = {180, 150, 7};
        grid.spacingMm = {0.27, 0.29, 1};
        grid.originMm = {-24.1, -19.7, 0};  // layers 0, 2, 4, 6 on the planes
        for (const double pixelMm : {1.0, 0.4})
            for (const bool fromSolid : {true, false}) {
                std::vector<std::size_t> inside;
                if (fromSolid) {
                    RoiReconstructOptions options;
                    options.reconstruction.pixelMm = pixelMm;
                    const RoiSurface solid = reconstructRoi(cpuRuntime(), roi, options);
                    ASSERT_TRUE(solid.check.validSolid());
                    inside = roiSolidVoxelsInside(roi, solid, grid);
                } else {
                    RoiFieldOptions options;
                    options.pixelMm = pixelMm;
                    inside = roiVoxelsInside(cpuRuntime(), roi, grid, options);
                }
                std::size_t checked = 0, wrong = 0;
                for (const Slice& slice : roi.slices) {
                    const int k = int(std::lround(slice.zMm));
                    for (int j = 0; j < grid.size[1]; ++j)
                        for (int i = 0; i < grid.size[0]; ++i) {
                            const Vec3 p = grid.worldOfIndex(i, j, k);
                            const bool expected = insideByWinding(slice, {p.x, p.y});
                            const bool got = std::binary_search(inside.begin(), inside.end(),
                                                                grid.linearIndex(i, j, k));
                            ++checked;
                            wrong += expected != got;
                        }
                }
                EXPECT_EQ(wrong, 0u) << "seed " << seed << ", pixel " << pixelMm << " mm, "
                                     << (fromSolid ? "solid" : "field") << ", of " << checked;
            }
    }
}

TEST(RasterizeOnPlanes, PlanesLeftEmptyFillNothing) {
    ContourSet set;
    const Polygon square{{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
    Roi body, node;
    body.name = "Body";
    node.name = "Node";
    for (double z = 0; z <= 10; z += 1) body.slices.push_back({z, {circlePolygon({0, 0}, 30, 64)}});
    for (double z : {0.0, 1.0, 2.0, 6.0, 7.0}) node.slices.push_back({z, {square}});
    set.rois = {body, node};
    findPlaneGaps(set);
    ASSERT_EQ(set.rois[1].restartsAt, std::vector<std::size_t>{3});
    VolumeGeometry grid;
    grid.size = {25, 25, 21};
    grid.spacingMm = {1, 1, 0.5};
    grid.originMm = {-12.5, -12.5, -0.5};
    const RoiSurface solid = reconstructRoi(cpuRuntime(), set.rois[1]);
    ASSERT_TRUE(solid.check.validSolid());
    for (const bool fromSolid : {false, true}) {
        const std::vector<std::size_t> inside =
            fromSolid ? roiSolidVoxelsInside(set.rois[1], solid, grid)
                      : roiVoxelsInside(cpuRuntime(), set.rois[1], grid);
        // Voxel layers at z = 3, 4 and 5 mm lie in the gap: nothing there
        // (the caps reach half a plane spacing, 0.5 mm, into it).
        for (std::size_t v : inside) {
            const double z = grid.worldOfIndex(0, 0, int(v / (25 * 25))).z;
            EXPECT_TRUE(z < 2.6 || z > 5.4) << z << (fromSolid ? " (solid)" : " (field)");
        }
        // The runs' own planes are filled: 10 × 10 centres on each.
        const auto onLayer = [&](double zMm) {
            const int k = int(std::lround((zMm + 0.5) / 0.5));
            return std::count_if(inside.begin(), inside.end(),
                                 [&](std::size_t v) { return int(v / (25 * 25)) == k; });
        };
        EXPECT_EQ(onLayer(1), 100);
        EXPECT_EQ(onLayer(7), 100);
        EXPECT_EQ(onLayer(4), 0);
    }
}

// Blobs of anatomy on 3 mm planes (an ellipsoid with a wobbling outline,
// 1 to 60 cc), as a planning system would draw an organ or a GTV.
Roi blob(std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> size(7, 26), phase(0, 6.28), offset(-0.5, 0.5);
    const double a = size(random), b = 0.6 * size(random) + 3, c = size(random) / 1.5 + 4;
    const double p = phase(random), z0 = offset(random);
    Roi roi;
    roi.name = "Blob";
    for (double z = z0 - c + 1.5; z < z0 + c; z += 3) {
        const double t = (z - z0) / c, s = std::sqrt(1 - t * t);
        Polygon outline;
        for (int k = 0; k < 72; ++k) {
            const double u = 2 * 3.14159265358979 * k / 72;
            const double r = s * (1 + 0.12 * std::sin(3 * u + p + z / 7));
            outline.push_back({a * r * std::cos(u) + 0.3 * z, b * r * std::sin(u)});
        }
        roi.slices.push_back({z, {outline}});
    }
    return roi;
}

TEST(RasterizeFromSolid, LabelMapVolumeIsTheSurfacesOnItsOwnGrid) {
    // rasterize --voxel-mm on 3 mm planes: the voxels' volume within 1 % of
    // the surface's at 1 mm voxels and 0.2 % at 0.5 mm for every blob of a
    // cc or more (docs/cli.md gives the measured numbers on real sets).
    int measured = 0;
    for (std::uint32_t seed = 0; seed < 6; ++seed) {
        const Roi roi = blob(seed);
        const RoiSurface solid = reconstructRoi(cpuRuntime(), roi);
        ASSERT_TRUE(solid.check.validSolid()) << "seed " << seed;
        if (solid.check.volumeMm3 < 1000) continue;
        ++measured;
        for (const auto& [voxelMm, tolerance] : {std::pair{1.0, 0.01}, std::pair{0.5, 0.002}}) {
            const VolumeGeometry grid = gridAroundRois({&roi}, voxelMm);
            const std::size_t voxels = roiSolidVoxelsInside(roi, solid, grid).size();
            EXPECT_NEAR(double(voxels) * std::pow(voxelMm, 3), solid.check.volumeMm3,
                        tolerance * solid.check.volumeMm3)
                << "seed " << seed << ", " << voxelMm << " mm voxels";
        }
    }
    EXPECT_GE(measured, 4);
}

}  // namespace
}  // namespace dfrecon
