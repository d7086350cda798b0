// The 3D field: kernel against the C++ reference, and against exact
// distances where the reconstructed solid is known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "field/DistanceField3D.hpp"
#include "field/FieldVolume.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

SliceFields fieldsOf(const std::vector<Slice>& slices, double pixelMm) {
    return computeSliceFields(cpuRuntime(), slices, gridForSlices(slices, pixelMm));
}

TEST(DistanceField3D, KernelMatchesReferenceWithUnevenGaps) {
    SynthOptions options;
    options.spacingMm = 3;
    ContourSet set = sliceShape(*makeShape("torus"), options);
    std::vector<Slice> slices = set.rois[0].slices;
    slices.erase(slices.begin() + 2);  // a double gap in the middle
    const SliceFields fields = fieldsOf(slices, 0.5);
    DistanceField3D onDevice = layersFromSlices(fields, 3), reference = onDevice;
    propagateAlongZ(cpuRuntime(), onDevice);
    propagateAlongZReference(reference);
    ASSERT_EQ(onDevice.distanceMm.size(), reference.distanceMm.size());
    for (std::size_t k = 0; k < reference.distanceMm.size(); ++k)
        ASSERT_NEAR(onDevice.distanceMm[k], reference.distanceMm[k],
                    1e-5f * (1 + std::fabs(reference.distanceMm[k])))
            << k;
}

TEST(DistanceField3D, KeepsSignsAndOnlyShrinksDistances) {
    const ContourSet set = sliceShape(*makeShape("y"), {});
    const SliceFields fields = fieldsOf(set.rois[0].slices, 0.5);
    DistanceField3D field = layersFromSlices(fields, 2);
    const DistanceField3D before = field;
    propagateAlongZReference(field);
    for (std::size_t k = 0; k < field.distanceMm.size(); ++k) {
        ASSERT_EQ(field.distanceMm[k] < 0, before.distanceMm[k] < 0) << k;
        ASSERT_LE(std::fabs(field.distanceMm[k]), std::fabs(before.distanceMm[k]) + 1e-6f);
    }
}

// A stack of identical discs is the cylinder r = 6, |z| <= 4 + 1 (the caps
// half a spacing out), whose exact distance is known.
double cylinderDistance(double x, double y, double z) {
    const double radial = std::hypot(x, y) - 6, axial = std::fabs(z) - 5;
    if (radial <= 0 && axial <= 0) return std::max(radial, axial);
    return std::hypot(std::max(radial, 0.0), std::max(axial, 0.0));
}

TEST(DistanceField3D, ConservativeAndExactOnTheSidesOfACylinder) {
    std::vector<Slice> slices;
    for (int s = -2; s <= 2; ++s) slices.push_back({2.0 * s, {circlePolygon({0, 0}, 6, 400)}});
    const SliceFields fields = fieldsOf(slices, 0.25);
    DistanceField3D field = layersFromSlices(fields, 2);
    propagateAlongZ(cpuRuntime(), field);
    // The 400-gon is within 2e-3 mm of the circle; fields are exact otherwise.
    const double polygonError = 6 * (1 - std::cos(M_PI / 400)) + 1e-4;
    for (std::size_t layer = 0; layer < field.layerCount(); ++layer)
        for (int j = 0; j < field.grid.height; j += 3)
            for (int i = 0; i < field.grid.width; i += 3) {
                const Point2 p = field.grid.pixelCentre(i, j);
                const double d = field.distanceMm[field.index(layer, i, j)];
                const double exact = cylinderDistance(p.x, p.y, field.zMm[layer]);
                ASSERT_EQ(d < 0, exact < 0) << p.x << " " << p.y << " " << field.zMm[layer];
                // Never closer than the truth (the double-cone metric)...
                ASSERT_GE(std::fabs(d), std::fabs(exact) - polygonError);
                // ...and exact beside the side, inside the slab range.
                if (std::fabs(field.zMm[layer]) <= 4 && exact > 0) {
                    ASSERT_NEAR(d, exact, polygonError);
                }
            }
}

TEST(DistanceField3D, ResamplingHitsLayersExactlyAndInterpolatesBetween) {
    std::vector<Slice> slices;
    for (int s = 0; s < 3; ++s) slices.push_back({2.0 * s, {circlePolygon({0, 0}, 5, 64)}});
    DistanceField3D field = layersFromSlices(fieldsOf(slices, 0.5), 2);
    propagateAlongZReference(field);
    const DenseDistanceVolume volume = resampleAlongZ(field, 1.0);
    EXPECT_EQ(volume.nz, 9);  // layers at -2, -1 (cap), 0, 2, 4, 5 (cap), 6
    EXPECT_DOUBLE_EQ(volume.originMm[2], -2.0);
    const std::size_t pixels = field.grid.pixelCount();
    for (std::size_t p = 0; p < pixels; p += 97) {
        // z = 0 is layer 2; z = 1 lies half-way between layers 2 and 3.
        EXPECT_FLOAT_EQ(volume.valuesMm[2 * pixels + p], field.distanceMm[2 * pixels + p]);
        EXPECT_NEAR(volume.valuesMm[3 * pixels + p],
                    0.5f * (field.distanceMm[2 * pixels + p] + field.distanceMm[3 * pixels + p]),
                    1e-5);
    }
}

}  // namespace
}  // namespace dfrecon
