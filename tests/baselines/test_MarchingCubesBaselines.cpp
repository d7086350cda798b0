// The marching-cubes baselines on analytic shapes: closed solids with the
// planning-system volume (shape-based interpolation also near the surface).
#include <gtest/gtest.h>

#include <cmath>

#include "baselines/MarchingCubesBaselines.hpp"
#include "geometry/MeshCheck.hpp"
#include "shapes/AnalyticShapes.hpp"

using namespace dfrecon;

TEST(LevinBaseline, SphereAndTorusAreValidSolidsNearTheSurface) {
    ocl::Runtime runtime("cpu");
    for (const char* name : {"sphere", "torus", "y"}) {
        SCOPED_TRACE(name);
        const auto shape = makeShape(name);
        SynthOptions options;
        options.spacingMm = 2;
        options.pointsPerContour = 128;
        const ContourSet set = sliceShape(*shape, options);
        const std::vector<Slice>& slices = set.rois[0].slices;
        const SliceFields fields = computeSliceFields(runtime, slices, gridForSlices(slices, 0.5));
        const TriMesh mesh = levinBaseline(fields);
        const MeshCheckReport report = checkMesh(toTriangleSoup(mesh));
        EXPECT_TRUE(report.validSolid()) << report.intersectingPairs << " " << report.boundaryEdges;
        EXPECT_EQ(report.genus, std::string(name) == "torus" ? 1 : 0);
        // Slab volume: the slices' area times spacing, which the caps reproduce.
        double slab = 0;
        for (const Slice& s : slices)
            for (const Polygon& c : s.contours) slab += signedArea(c) * options.spacingMm;
        EXPECT_NEAR(report.volumeMm3 / slab, 1, 0.03);
        double worst = 0, sum = 0;
        for (auto v : mesh.vertices()) {
            const auto p = mesh.point(v);
            const double d = std::abs(shape->signedDistance({p[0], p[1], p[2]}));
            worst = std::max(worst, d);
            sum += d;
        }
        EXPECT_LT(sum / double(mesh.n_vertices()), 0.6);  // staircase and caps included
        EXPECT_LT(worst, 2.5);
    }
}

TEST(RasterBaseline, SphereAndTorusAreClosedWithThePlanningVolume) {
    for (const char* name : {"sphere", "torus"}) {
        SCOPED_TRACE(name);
        SynthOptions options;
        options.spacingMm = 2;
        options.pointsPerContour = 128;
        const ContourSet set = sliceShape(*makeShape(name), options);
        const TriangleSoup soup = rasterBaseline(set.rois[0], 0.5);
        const MeshCheckReport report = checkMesh(soup);
        EXPECT_TRUE(report.watertight()) << report.boundaryEdges << " " << report.nonManifoldEdges;
        EXPECT_GT(report.volumeMm3, 0) << "normals point outward";
        EXPECT_EQ(report.genus, std::string(name) == "torus" ? 1 : 0);
        // Each plane one spacing thick: the volume planning systems count.
        EXPECT_NEAR(report.volumeMm3 / contourVolumeMm3(set.rois[0]), 1, 0.03);
    }
}
