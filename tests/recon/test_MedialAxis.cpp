// Medial axes between neighbouring slices: the sum kernel against its
// reference, and the traced chains against what the geometry dictates
// (concentric circles: the circle halfway; one contour to two: one axis
// enclosing both; a contour with a hole to one without: outer and hole
// borders).
#include <gtest/gtest.h>

#include <cmath>

#include "recon/MedialAxis.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/CpuRuntime.hpp"

using namespace dfrecon;

namespace {

Polygon circle(Point2 c, double r, int n, bool ccw = true) {
    return circlePolygon(c, r, n, !ccw);
}

struct Pair {
    SliceFields fields;
    SliceSum sum;
    std::vector<MedialAxis> axes;
};

Pair medialAxesOf(const std::vector<Polygon>& lower, const std::vector<Polygon>& upper,
                  double pixelMm) {
    std::vector<Slice> slices(2);
    slices[0] = {0, lower};
    slices[1] = {2, upper};
    for (Slice& s : slices) normaliseOrientation(s);
    Pair pair;
    pair.fields = computeSliceFields(cpuRuntime(), slices, gridForSlices(slices, pixelMm));
    pair.sum = sumSlices(pair.fields, 0, 1);
    pair.axes = traceMedialAxes(pair.fields, 0, 1, pair.sum);
    return pair;
}

// Every chain is closed and 8-connected, and each pixel is a border pixel of
// the negative region: S < 0 here and S >= 0 at a 4-neighbour.
void expectWellFormed(const Pair& pair) {
    const SliceGrid& g = pair.fields.grid;
    auto sumAt = [&](int i, int j) {
        return pair.sum.sumMm[std::size_t(j) * std::size_t(g.width) + std::size_t(i)];
    };
    for (const MedialAxis& axis : pair.axes) {
        ASSERT_FALSE(axis.pixels.empty());
        for (std::size_t k = 0; k < axis.pixels.size(); ++k) {
            const MedialPixel& p = axis.pixels[k];
            const MedialPixel& q = axis.pixels[(k + 1) % axis.pixels.size()];
            EXPECT_LE(std::max(std::abs(p.i - q.i), std::abs(p.j - q.j)), 1);
            EXPECT_LT(p.sumMm, 0);
            EXPECT_GE(p.sumMm, -2 * g.pixelMm * 1.0001);  // S is 2-Lipschitz
            bool outsideNeighbour = false;
            const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
            for (int n = 0; n < 4; ++n) {
                const int i = p.i + di[n], j = p.j + dj[n];
                outsideNeighbour |=
                    i < 0 || j < 0 || i >= g.width || j >= g.height || sumAt(i, j) >= 0;
            }
            EXPECT_TRUE(outsideNeighbour) << p.i << "," << p.j;
            const std::size_t at = pair.fields.index(0, p.i, p.j);
            EXPECT_EQ(p.lowerId, pair.fields.nearestId[at]);
            EXPECT_EQ(p.upperId, pair.fields.nearestId[pair.fields.index(1, p.i, p.j)]);
        }
    }
}

double chainArea(const MedialAxis& axis, const SliceGrid& g) {
    Polygon p;
    for (const MedialPixel& m : axis.pixels) p.push_back(g.pixelCentre(m.i, m.j));
    return signedArea(p);
}

}  // namespace

TEST(MedialAxis, SumIsTheFloatSumAndZeroCountsAsPositive) {
    const ContourSet set = sliceShape(*makeShape("y"), {});
    const std::vector<Slice>& slices = set.rois[0].slices;
    const SliceFields fields = computeSliceFields(cpuRuntime(), slices, gridForSlices(slices, 0.4));
    const std::size_t pixels = fields.grid.pixelCount();
    for (std::size_t s = 0; s + 1 < slices.size(); ++s) {
        const SliceSum sum = sumSlices(fields, s, s + 1);
        for (std::size_t k = 0; k < pixels; ++k) {
            const float expected =
                fields.distanceMm[s * pixels + k] + fields.distanceMm[(s + 1) * pixels + k];
            ASSERT_EQ(sum.sumMm[k], expected);
            ASSERT_EQ(sum.negative[k], expected < 0 ? 1 : 0);
        }
    }
}

TEST(MedialAxis, ConcentricCirclesGiveTheCircleHalfway) {
    const Pair pair = medialAxesOf({circle({0, 0}, 10, 200)}, {circle({0, 0}, 14, 200)}, 0.1);
    ASSERT_EQ(pair.axes.size(), 1u);
    expectWellFormed(pair);
    const SliceGrid& g = pair.fields.grid;
    for (const MedialPixel& p : pair.axes[0].pixels) {
        // S = 2ρ - 24 (up to the polygons' sag), so the border is at ρ ≈ 12.
        EXPECT_NEAR(length(g.pixelCentre(p.i, p.j)), 12, 1.5 * g.pixelMm);
        EXPECT_FALSE(PrimitiveId::decode(p.lowerId).contour != 0);
    }
    EXPECT_GT(chainArea(pair.axes[0], g), 0);  // outer borders counter-clockwise
}

TEST(MedialAxis, OneContourToTwoGivesOneAxisAroundBoth) {
    // A wide ellipse-like blob below, two circles above: S < 0 wherever
    // the pair overlaps enough, one connected region reaching both circles.
    const Pair pair = medialAxesOf({circle({0, 0}, 12, 160)},
                                   {circle({-7, 0}, 5, 80), circle({7, 0}, 5, 80)}, 0.15);
    expectWellFormed(pair);
    ASSERT_EQ(pair.axes.size(), 1u);
    bool seesLeft = false, seesRight = false;
    for (const MedialPixel& p : pair.axes[0].pixels) {
        const PrimitiveId upper = PrimitiveId::decode(p.upperId);
        seesLeft |= upper.contour == 0;
        seesRight |= upper.contour == 1;
    }
    EXPECT_TRUE(seesLeft && seesRight);  // correspondences reach both upper contours
}

TEST(MedialAxis, HoleGivesAHoleBorder) {
    // Annuli 20/6 below and 18/10 above: S is negative in a ring and
    // non-negative inside ρ = 8, so there is an outer and a hole border.
    const Pair pair = medialAxesOf({circle({0, 0}, 20, 200), circle({0, 0}, 6, 100, false)},
                                   {circle({0, 0}, 18, 200), circle({0, 0}, 10, 100, false)}, 0.2);
    expectWellFormed(pair);
    ASSERT_EQ(pair.axes.size(), 2u);
    const MedialAxis& outer = pair.axes[0].bordersHole ? pair.axes[1] : pair.axes[0];
    const MedialAxis& hole = pair.axes[0].bordersHole ? pair.axes[0] : pair.axes[1];
    EXPECT_FALSE(outer.bordersHole);
    EXPECT_TRUE(hole.bordersHole);
    EXPECT_EQ(hole.parent, &outer == &pair.axes[0] ? 0 : 1);
    EXPECT_GT(chainArea(outer, pair.fields.grid), 0);
    EXPECT_LT(chainArea(hole, pair.fields.grid), 0);
    for (const MedialPixel& p : hole.pixels)  // S = (6 - ρ) + (10 - ρ) = 0 at ρ = 8
        EXPECT_NEAR(length(pair.fields.grid.pixelCentre(p.i, p.j)), 8,
                    1.5 * pair.fields.grid.pixelMm);
}

TEST(MedialAxis, DisjointContoursGiveNoAxis) {
    const Pair pair = medialAxesOf({circle({-30, 0}, 5, 60)}, {circle({30, 0}, 5, 60)}, 0.5);
    EXPECT_TRUE(pair.axes.empty());  // no overlap: no correspondence (caps handle these)
}
