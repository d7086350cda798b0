#include "segment/Segmentation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(Segmentation, UniformSphereGetsEqualCompactRegions) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(16));
    SegmentOptions options;
    options.regions = 12;
    options.speed = SpeedKind::Uniform;
    const Segmentation s = segmentMesh(graph, options);
    ASSERT_EQ(s.regions.size(), 12u);
    EXPECT_EQ(s.curvatureWeightMm, 0.0);
    double total = 0;
    std::vector<double> areas;
    for (const RegionReport& r : s.regions) {
        total += r.areaMm2;
        areas.push_back(r.areaMm2);
        EXPECT_TRUE(r.disk);
        EXPECT_GT(r.compactness, 0.75);  // a spherical pentagon: 0.8–0.9
    }
    EXPECT_NEAR(total, graph.totalArea(), 1e-9 * total);
    const double mean = total / 12;
    double variance = 0;
    for (double a : areas) variance += (a - mean) * (a - mean) / 12;
    EXPECT_LT(std::sqrt(variance) / mean, 0.1);
    EXPECT_EQ(s.faceRegion.size(), graph.triangles().size());
    EXPECT_EQ(s.vertexRegion.size(), std::size_t(graph.vertexCount()));
    for (int r : s.faceRegion) EXPECT_GE(r, 0);
    EXPECT_GE(s.energy.size(), 1u);
}

TEST(Segmentation, EveryComponentGetsRegions) {
    // Two spheres 10 radii apart: sampling from one never reaches the other.
    TriangleSoup two = geodesicSphere(8);
    const TriangleSoup other = geodesicSphere(6);
    const std::uint32_t offset = std::uint32_t(two.points.size());
    for (Vec3 p : other.points) two.points.push_back(p + Vec3{10, 0, 0});
    for (auto t : other.triangles)
        two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    const MeshGraph graph = MeshGraph::fromSoup(two);
    SegmentOptions options;
    options.regions = 6;
    options.speed = SpeedKind::Uniform;
    const Segmentation s = segmentMesh(graph, options);
    EXPECT_EQ(s.componentSeeds, 1);
    for (int r : s.faceRegion) EXPECT_GE(r, 0);
    for (const RegionReport& r : s.regions) EXPECT_TRUE(r.disk);
    // The second sphere, one seed, is split by the disk constraint.
    EXPECT_GE(s.seedsAdded, 1);
}

TEST(Segmentation, RejectsImpossibleRequests) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(2, 2, 1.0));
    SegmentOptions options;
    options.regions = 0;
    EXPECT_THROW(segmentMesh(graph, options), std::invalid_argument);
    options.regions = 10;
    EXPECT_THROW(segmentMesh(graph, options), std::invalid_argument);
}
