// Error-bounded simplification, checked by the independent verifier
// (simplify/SurfaceDistance: dense samples, exact distances over a BVH):
// both directions against the unsimplified mesh and against the contours,
// on every synth shape at three bounds.
#include <gtest/gtest.h>

#include "io/AnalyticShapes.hpp"
#include "recon/MeshCheck.hpp"
#include "recon/Reconstruction.hpp"
#include "simplify/Simplification.hpp"
#include "simplify/SurfaceDistance.hpp"

namespace dfrecon {
namespace {

ocl::Runtime& runtime() {
    static ocl::Runtime instance("cpu");
    return instance;
}

struct Case {
    Roi roi;
    TriangleSoup surface;
};

Case reconstructed(const std::string& shape, double spacingMm) {
    SynthOptions options;
    options.spacingMm = spacingMm;
    Case c;
    c.roi = sliceShape(*makeShape(shape), options).rois[0];
    c.surface = reconstructSurface(runtime(), c.roi).surface;
    return c;
}

// Runs the simplifier and the verifier; returns the simplified surface.
TriangleSoup simplifyAndVerify(const Case& c, double maxErrorMm) {
    SimplifyOptions options;
    options.maxErrorMm = maxErrorMm;
    const Simplified s = simplifySurface(&runtime(), c.surface, options);
    const MeshCheckReport before = checkMesh(c.surface), after = checkMesh(s.surface);
    EXPECT_TRUE(after.validSolid()) << "watertight " << after.watertight() << ", intersecting "
                                    << after.intersectingPairs;
    EXPECT_EQ(after.genus, before.genus);
    EXPECT_EQ(after.components, before.components);
    EXPECT_LT(s.stats.triangles, s.stats.trianglesBefore);
    EXPECT_LE(s.stats.surfaceToInputBoundMm, maxErrorMm);
    EXPECT_LE(s.stats.inputToSurfaceBoundMm, maxErrorMm);
    const TwoSidedDistance d = twoSidedDistance(c.surface, s.surface, 20000);
    EXPECT_LE(d.maxMm(), maxErrorMm);
    const SampledDistance contours =
        distanceToSurface(contourSamples(c.roi, maxErrorMm / 8), s.surface);
    EXPECT_LE(contours.maxMm, maxErrorMm);
    return s.surface;
}

TEST(Simplification, EverySynthShapeStaysWithinTheBoundBothWays) {
    for (const std::string& name : shapeNames())
        for (double bound : {0.25, 0.5, 1.0}) {
            SCOPED_TRACE(name + " at " + std::to_string(bound) + " mm");
            simplifyAndVerify(reconstructed(name, 2.0), bound);
        }
}

}  // namespace
}  // namespace dfrecon
