// Strips traced along a medial axis, on fields from the C++ reference (no
// device needed): positions go around once, and the strip is a closed band.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/MeshCheck.hpp"
#include "recon/StripStitching.hpp"

namespace dfrecon {
namespace {

Polygon circle(Point2 centre, double radius, int points) {
    return circlePolygon(centre, radius, points);
}

struct Band {
    std::vector<Slice> slices;
    SliceFields fields;
    std::vector<MedialAxis> axes;
};

Band bandBetween(Polygon lower, Polygon upper) {
    Band band;
    band.slices = {{0.0, {std::move(lower)}}, {2.0, {std::move(upper)}}};
    SliceGrid grid;
    grid.originMm = {-16, -16};
    grid.pixelMm = 0.25;
    grid.width = grid.height = 128;
    band.fields = computeSliceFieldsReference(band.slices, grid);
    band.axes = traceMedialAxes(band.fields, 0, 1, sumSlices(band.fields, 0, 1));
    return band;
}

TEST(StripStitching, PositionsGoAroundOnceInContourOrder) {
    // Shifted circles with different point counts.
    const Band band = bandBetween(circle({0, 0}, 10, 40), circle({2, 1}, 8, 25));
    ASSERT_EQ(band.axes.size(), 1u);
    for (int side = 0; side < 2; ++side) {
        const Polygon& contour = band.slices[std::size_t(side)].contours[0];
        const auto at = positionsAlongAxis(band.axes[0], band.fields.grid, contour, 0, side == 0);
        ASSERT_TRUE(at.has_value());
        ASSERT_EQ(at->positions.size(), contour.size());
        for (std::size_t i = 1; i < at->positions.size(); ++i)
            EXPECT_LE(at->positions[i - 1], at->positions[i]);
        EXPECT_LE(at->positions.back() - at->positions.front(), at->axisLength);
    }
}

TEST(StripStitching, ContourAgainstTheAxisIsRefused) {
    // A clockwise contour around a counter-clockwise axis: its indices run
    // backwards along the axis, so no strip can follow both.
    Polygon lower = circle({0, 0}, 10, 40);
    std::reverse(lower.begin(), lower.end());
    const Band band = bandBetween(lower, circle({0, 0}, 9, 30));
    ASSERT_EQ(band.axes.size(), 1u);
    EXPECT_FALSE(positionsAlongAxis(band.axes[0], band.fields.grid, lower, 0, true).has_value());
    EXPECT_TRUE(
        positionsAlongAxis(band.axes[0], band.fields.grid, band.slices[1].contours[0], 0, false)
            .has_value());
}

TEST(StripStitching, StripIsAnOutwardBandWithOneTrianglePerVertex) {
    const Band band = bandBetween(circle({0, 0}, 10, 40), circle({2, 1}, 8, 25));
    SurfaceBuilder builder;
    const Layer lower = makeLayer(builder, 0.0, band.slices[0].contours);
    const Layer upper = makeLayer(builder, 2.0, band.slices[1].contours);
    const auto lowerAt =
        positionsAlongAxis(band.axes[0], band.fields.grid, lower.contours[0], 0, true);
    const auto upperAt =
        positionsAlongAxis(band.axes[0], band.fields.grid, upper.contours[0], 0, false);
    ASSERT_TRUE(lowerAt && upperAt);
    stitchStrip(builder, lower.vertexIds[0], *lowerAt, upper.vertexIds[0], *upperAt);
    const TriangleSoup& band3d = builder.soup();
    EXPECT_EQ(band3d.triangles.size(), 40u + 25u);
    const MeshCheckReport check = checkMesh(band3d);
    EXPECT_EQ(check.boundaryEdges, 40u + 25u);  // the two contours, nothing else
    EXPECT_EQ(check.nonManifoldEdges + check.misorientedEdges + check.intersectingPairs, 0u);
    // Outward: every triangle's normal points away from the z axis.
    for (const auto& t : band3d.triangles) {
        const Vec3 a = band3d.points[t[0]], b = band3d.points[t[1]], c = band3d.points[t[2]];
        const Vec3 n = cross(b - a, c - a);
        const Vec3 centre = (1.0 / 3.0) * (a + b + c);
        EXPECT_GT(n.x * centre.x + n.y * centre.y, 0);
    }
}

}  // namespace
}  // namespace dfrecon
