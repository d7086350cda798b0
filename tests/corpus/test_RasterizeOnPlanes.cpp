// Label maps exact on the contour planes: every voxel centre on a plane is
// inside exactly when it is inside that plane's contours, checked against
// the winding numbers at each centre (brute force), whatever the field's
// pixel size; planes left empty inside an ROI fill nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "contours/PlaneGaps.hpp"
#include "dfrecon/Field.hpp"
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
        for (const double pixelMm : {1.0, 0.4}) {
            RoiFieldOptions options;
            options.pixelMm = pixelMm;
            const std::vector<std::size_t> inside =
                roiVoxelsInside(cpuRuntime(), roi, grid, options);
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
            EXPECT_EQ(wrong, 0u) << "seed " << seed << ", pixel " << pixelMm << " mm, of "
                                 << checked;
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
    const std::vector<std::size_t> inside = roiVoxelsInside(cpuRuntime(), set.rois[1], grid);
    // Voxel layers at z = 3, 4 and 5 mm lie in the gap: nothing there.
    for (std::size_t v : inside) {
        const double z = grid.worldOfIndex(0, 0, int(v / (25 * 25))).z;
        EXPECT_TRUE(z < 2.6 || z > 5.4) << z;
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

}  // namespace
}  // namespace dfrecon
