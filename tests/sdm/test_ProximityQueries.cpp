// Proximity queries on boxes, whose exact distances are known: separation
// within [exact, exact + bound], collisions exact, containment, and the
// deepest point's depth within its bound.
#include <gtest/gtest.h>

#include "sdm/ProximityQueries.hpp"
#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

namespace {

std::vector<PairProximity> query(const SurfaceScene& scene, int atlasSize) {
    std::vector<ObjectSamples> samples;
    for (std::size_t o = 0; o < scene.objectCount(); ++o)
        samples.push_back(sampleObject(scene, o, {atlasSize}));
    return proximityQueries(scene, samples,
                            [&](const std::vector<SurfaceSample>& s, const DistanceQuery& q) {
                                return closestPrimitivesReference(scene, s, q);
                            });
}

}  // namespace

TEST(ProximityQueries, SeparatedBoxesGiveTheGapWithinTheBound) {
    // Facing faces 3 mm apart, offset sideways so the closest pair is not
    // a vertex pair.
    SurfaceScene scene(
        {boxMesh({0, 0, 0}, {10, 10, 10}, 3), boxMesh({13, 4.3, 2.2}, {20, 20, 6}, 3)});
    const auto pairs = query(scene, 64);
    ASSERT_EQ(pairs.size(), 1u);
    const PairProximity& p = pairs[0];
    EXPECT_FALSE(p.colliding());
    EXPECT_GE(p.separationMm, 3 - 1e-9);
    EXPECT_LE(p.separationMm, 3 + p.boundMm);
    EXPECT_NEAR(p.pointOnFirst.x, 10, 1e-9);
    EXPECT_NEAR(p.pointOnSecond.x, 13, 1e-9);
    EXPECT_NEAR(length(p.pointOnFirst - p.pointOnSecond), p.separationMm, 1e-9);
    EXPECT_EQ(p.deepestPointMm, 0);
}

TEST(ProximityQueries, OverlappingBoxesCollideAndReportTheirDepth) {
    // The second box reaches 2 mm into the first through its +x face.
    SurfaceScene scene({boxMesh({0, 0, 0}, {10, 10, 10}, 3), boxMesh({8, 2, 2}, {20, 8, 8}, 3)});
    const auto pairs = query(scene, 128);
    const PairProximity& p = pairs[0];
    EXPECT_TRUE(p.surfacesIntersect);
    EXPECT_TRUE(p.colliding());
    EXPECT_EQ(p.separationMm, 0);
    // The deepest point of the second box in the first is its x = 8 face,
    // 2 mm inside; of the first in the second, the x = 10 face, 2 mm in.
    EXPECT_LE(p.deepestPointMm, 2 + 1e-9);
    EXPECT_GE(p.deepestPointMm, 2 - p.depthBoundMm);
}

TEST(ProximityQueries, NestedBoxesAreContainedWithoutCrossing) {
    SurfaceScene scene({boxMesh({0, 0, 0}, {10, 10, 10}, 2), boxMesh({3, 3, 3}, {6, 6, 6}, 2),
                        boxMesh({30, 0, 0}, {31, 1, 1}, 1)});
    const auto pairs = query(scene, 64);
    ASSERT_EQ(pairs.size(), 3u);
    const PairProximity& nested = pairs[0];  // (0, 1)
    EXPECT_FALSE(nested.surfacesIntersect);
    EXPECT_TRUE(nested.secondInsideFirst);
    EXPECT_FALSE(nested.firstInsideSecond);
    EXPECT_TRUE(nested.colliding());
    // The inner box's surface points deepest in the outer box, e.g.
    // (5, 6, 5), are 4 mm from its nearest face.
    EXPECT_LE(nested.deepestPointMm, 4 + 1e-9);
    EXPECT_GE(nested.deepestPointMm, 4 - nested.depthBoundMm);
    const PairProximity& far = pairs[1];  // (0, 2)
    EXPECT_FALSE(far.colliding());
    EXPECT_GE(far.separationMm, 20 - 1e-9);
    EXPECT_LE(far.separationMm, 20 + far.boundMm);
}
