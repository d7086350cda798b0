// Smooth interpolation between planes: the interpolant against its defining
// properties, and smooth reconstructions against analytic surfaces (exact
// signed distances), their linear counterparts and the contour points.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include "geometry/MeshCheck.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/SliceInterpolant.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/SurfaceDistance.hpp"

namespace dfrecon {
namespace {

ocl::Runtime& runtime() {
    static ocl::Runtime instance("cpu");
    return instance;
}

double meanDistance(const AnalyticShape& shape, const TriangleSoup& soup, double zLo, double zHi) {
    double sum = 0;
    std::size_t count = 0;
    for (const Vec3& p : sampleTriangles(soup, 20000, 5))
        if (p.z >= zLo && p.z <= zHi) sum += std::abs(shape.signedDistance(p)), ++count;
    return sum / double(std::max<std::size_t>(1, count));
}

}  // namespace

TEST(SliceInterpolant, EqualsEachPlaneAndStaysBetweenNeighbours) {
    SynthOptions options;
    options.spacingMm = 3;
    const ContourSet set = sliceShape(*makeShape("ellipsoid"), options);
    const std::vector<Slice>& slices = set.rois[0].slices;
    const SliceFields fields = computeSliceFields(runtime(), slices, gridForSlices(slices, 0.5));
    const SliceInterpolant field(fields);
    std::mt19937 random(3);
    for (std::size_t s = 0; s + 1 < slices.size(); ++s)
        for (int k = 0; k < 50; ++k) {
            const int i = std::uniform_int_distribution<int>(0, fields.grid.width - 1)(random);
            const int j = std::uniform_int_distribution<int>(0, fields.grid.height - 1)(random);
            const Point2 c = fields.grid.pixelCentre(i, j);
            const double v0 = fields.distanceMm[fields.index(s, i, j)];
            const double v1 = fields.distanceMm[fields.index(s + 1, i, j)];
            // On a plane: the field at the pixel centre (bilinear is exact there).
            EXPECT_NEAR(field.value({c.x, c.y, fields.zMm[s]}), v0, 1e-6);
            // Between: never outside the two planes' values (monotone cubic).
            for (double t : {0.1, 0.37, 0.5, 0.81}) {
                const double z = fields.zMm[s] + t * (fields.zMm[s + 1] - fields.zMm[s]);
                const double f = field.value({c.x, c.y, z});
                EXPECT_GE(f, std::min(v0, v1) - 1e-9);
                EXPECT_LE(f, std::max(v0, v1) + 1e-9);
            }
        }
}

TEST(SmoothInterpolation, CloserToRoundShapesThroughEveryContourPointAndValid) {
    for (const char* name : {"sphere", "ellipsoid", "hollow-sphere"})
        for (double spacing : {2.0, 5.0}) {
            const auto shape = makeShape(name);
            SynthOptions options;
            options.spacingMm = spacing;
            const ContourSet set = sliceShape(*shape, options);
            const Roi& roi = set.rois[0];
            const Reconstruction linear = reconstructSurface(runtime(), roi);
            ReconstructionOptions smoothOptions;
            smoothOptions.interpolation = Interpolation::Smooth;
            const Reconstruction smooth = reconstructSurface(runtime(), roi, smoothOptions);
            const std::string label = std::string(name) + " " + std::to_string(spacing);
            ASSERT_TRUE(smooth.check.validSolid()) << label;
            EXPECT_TRUE(checkMesh(smooth.surface).validSolid()) << label;
            EXPECT_FALSE(smooth.stats.smoothFellBack) << label;
            EXPECT_GT(smooth.stats.smoothedVertices, 0u) << label;
            // Every contour point is a vertex (to float precision).
            std::set<std::tuple<float, float, float>> vertices;
            for (const Vec3& p : smooth.surface.points)
                vertices.insert({float(p.x), float(p.y), float(p.z)});
            for (const Slice& slice : roi.slices)
                for (const Polygon& contour : slice.contours)
                    for (Point2 p : contour)
                        ASSERT_TRUE(vertices.count({float(p.x), float(p.y), float(slice.zMm)}))
                            << label;
            // Between the first and last plane (the caps are the same in
            // both modes), closer to the true surface than straight strips.
            const double lo = roi.slices.front().zMm, hi = roi.slices.back().zMm;
            const double smoothMean = meanDistance(*shape, smooth.surface, lo, hi);
            const double linearMean = meanDistance(*shape, linear.surface, lo, hi);
            EXPECT_LT(smoothMean, linearMean) << label;
        }
}

}  // namespace dfrecon
