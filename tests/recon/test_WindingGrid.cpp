// The winding-number kernel against its C++ reference on the PoCL CPU device.
// Tolerance: they must agree exactly except at pixel centres within 1e-3 mm of
// a contour, where float32 rounding may decide differently.
#include <gtest/gtest.h>

#include <random>

#include "io/AnalyticShapes.hpp"
#include "recon/WindingGrid.hpp"

using namespace dfrecon;

namespace {

void expectAgreement(ocl::Runtime& runtime, const std::vector<Polygon>& contours,
                     const SliceGrid& grid) {
    const std::vector<int> kernel = windingGrid(runtime, contours, grid);
    const std::vector<int> reference = windingGridReference(contours, grid);
    ASSERT_EQ(kernel.size(), reference.size());
    int inside = 0, mismatches = 0;
    for (int j = 0; j < grid.height; ++j)
        for (int i = 0; i < grid.width; ++i) {
            const std::size_t k = std::size_t(j) * std::size_t(grid.width) + std::size_t(i);
            inside += reference[k] != 0;
            if (kernel[k] == reference[k]) continue;
            double nearest = INFINITY;
            for (const Polygon& c : contours)
                nearest = std::min(nearest, distanceToBoundary(grid.pixelCentre(i, j), c));
            EXPECT_LT(nearest, 1e-3) << "pixel " << i << "," << j;
            ++mismatches;
        }
    EXPECT_GT(inside, 0);
    EXPECT_LE(mismatches, 2);
}

}  // namespace

TEST(WindingGrid, KernelMatchesReferenceOnShapeSlices) {
    ocl::Runtime runtime("cpu");
    for (const std::string& name : shapeNames()) {
        SynthOptions options;
        options.spacingMm = 5;
        options.noiseMm = 0.05;
        const ContourSet set = sliceShape(*makeShape(name), options);
        for (const Slice& slice : set.rois[0].slices) {
            Box2 box;
            for (const Polygon& c : slice.contours)
                for (Point2 p : c) box.add(p);
            // Odd pixel size and origin far from zero: relative coordinates matter.
            SliceGrid grid = gridAround(box, 0.37, 3);
            expectAgreement(runtime, slice.contours, grid);
        }
    }
}

TEST(WindingGrid, HolesGiveZeroAndIslandsOne) {
    ocl::Runtime runtime("cpu");
    const Polygon outer{{0, 0}, {30, 0}, {30, 30}, {0, 30}};
    const Polygon hole{{5, 5}, {5, 25}, {25, 25}, {25, 5}};
    const Polygon island{{10, 10}, {20, 10}, {20, 20}, {10, 20}};
    SliceGrid grid;
    grid.originMm = {1000, -500};  // far from the origin
    grid.pixelMm = 1;
    grid.width = grid.height = 32;
    std::vector<Polygon> contours;
    for (Polygon c : {outer, hole, island}) {
        for (Point2& p : c) p = p + grid.originMm;
        contours.push_back(c);
    }
    const std::vector<int> w = windingGrid(runtime, contours, grid);
    EXPECT_EQ(w[2 * 32 + 2], 1);    // in the ring
    EXPECT_EQ(w[7 * 32 + 7], 0);    // in the hole
    EXPECT_EQ(w[15 * 32 + 15], 1);  // on the island
    EXPECT_EQ(w[31 * 32 + 31], 0);  // outside
    expectAgreement(runtime, contours, grid);
}
