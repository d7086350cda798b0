#include "segment/GeodesicVoronoi.hpp"

#include <gtest/gtest.h>

#include <numeric>

#include "tests/segment/SegmentTestMeshes.hpp"

using namespace dfrecon;
using dfrecon::testing::nearestVertex;

namespace {

struct Solved {
    MeshGraph graph;
    UpdateStencils stencils;
    FastMarching marching;
    GeodesicField field;
    VoronoiRegions regions;
    Solved(MeshGraph g, const std::vector<Vec3>& sites)
        : graph(std::move(g)), stencils(graph), marching(stencils) {
        std::vector<GeodesicSource> sources;
        for (std::size_t i = 0; i < sites.size(); ++i)
            sources.push_back({nearestVertex(graph, sites[i]), 0.0, int(i)});
        field = marching.solve(sources);
        regions = geodesicVoronoi(graph, marching, field, int(sites.size()));
    }
};

}  // namespace

TEST(GeodesicVoronoi, InterpolatedBordersSplitASquareExactly) {
    // Two sites symmetric about x = 0.5 on a grid whose vertices miss that
    // line (31 columns): vertex labels alone would give 16/31 vs 15/31 of
    // the area; the interpolated border gives halves.
    const Vec3 left{10.0 / 31, 15.0 / 31, 0}, right{21.0 / 31, 15.0 / 31, 0};
    const Solved s(MeshGraph::fromSoup(squareGrid(31, 31, 1.0 / 31)), {left, right});
    ASSERT_NEAR(length(s.graph.point(nearestVertex(s.graph, left)) - left), 0, 1e-12);
    EXPECT_NEAR(s.regions.area[0], 0.5, 0.005);
    EXPECT_NEAR(s.regions.area[1], 0.5, 0.005);
    // The border is the line x = 0.5, length 1.
    EXPECT_NEAR(s.regions.borderLength, 1.0, 0.02);
    // Perimeter: border plus three sides of the half square.
    EXPECT_NEAR(s.regions.perimeter[0], 3.0, 0.03);
    EXPECT_EQ(s.regions.neighbours[0], std::vector<int>{1});
    for (int t = 0; t < s.graph.triangleCount(); ++t) {
        const auto& tri = s.graph.triangle(t);
        const double cx =
            (s.graph.point(tri[0]).x + s.graph.point(tri[1]).x + s.graph.point(tri[2]).x) / 3;
        if (std::abs(cx - 0.5) > 0.05) {
            EXPECT_EQ(s.regions.faceRegion[std::size_t(t)], cx < 0.5 ? 0 : 1);
        }
    }
}

TEST(GeodesicVoronoi, AreasAddUpToTheSurfaceAndAdjacencyIsMutual) {
    const Solved s(
        MeshGraph::fromSoup(geodesicSphere(20)),
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0.6, 0.6, 0.5}});
    const double total = std::accumulate(s.regions.area.begin(), s.regions.area.end(), 0.0);
    EXPECT_NEAR(total, s.graph.totalArea(), 1e-9 * total);
    for (int r = 0; r < 7; ++r) {
        EXPECT_GT(s.regions.area[std::size_t(r)], 0);
        // On the unit sphere the isoperimetric inequality is P² ≥ 4πA − A²
        // (equality for caps), so 4πA/P² may exceed 1 but not 4π/(4π − A).
        const double a = s.regions.area[std::size_t(r)];
        EXPECT_GT(s.regions.compactness(r), 0.5);
        EXPECT_LE(s.regions.compactness(r), 4 * M_PI / (4 * M_PI - a));
        for (int n : s.regions.neighbours[std::size_t(r)]) {
            const auto& back = s.regions.neighbours[std::size_t(n)];
            EXPECT_TRUE(std::find(back.begin(), back.end(), r) != back.end());
        }
    }
    // Octahedron-like sites: region 0 (+x) touches ±y, ±z and the extra site, not −x.
    const auto& n0 = s.regions.neighbours[0];
    EXPECT_TRUE(std::find(n0.begin(), n0.end(), 3) == n0.end());
    EXPECT_TRUE(std::find(n0.begin(), n0.end(), 1) != n0.end());
}

TEST(GeodesicVoronoi, TopologyTellsDisksFromSpheresAndAnnuli) {
    const MeshGraph sphere = MeshGraph::fromSoup(geodesicSphere(6));
    std::vector<int> one(sphere.triangles().size(), 0);
    RegionTopology whole = regionTopology(sphere, one, 1)[0];
    EXPECT_EQ(whole.eulerCharacteristic, 2);
    EXPECT_EQ(whole.boundaryLoops, 0);
    EXPECT_FALSE(whole.isDisk());
    // Hemispheres and a band around the equator: disk, annulus, disk.
    std::vector<int> bands(sphere.triangles().size());
    for (int t = 0; t < sphere.triangleCount(); ++t) {
        const auto& tri = sphere.triangle(t);
        const double z =
            (sphere.point(tri[0]).z + sphere.point(tri[1]).z + sphere.point(tri[2]).z) / 3;
        bands[std::size_t(t)] = z > 0.4 ? 0 : z < -0.4 ? 2 : 1;
    }
    const auto topology = regionTopology(sphere, bands, 3);
    EXPECT_TRUE(topology[0].isDisk());
    EXPECT_TRUE(topology[2].isDisk());
    EXPECT_EQ(topology[1].eulerCharacteristic, 0);
    EXPECT_EQ(topology[1].boundaryLoops, 2);
    EXPECT_FALSE(topology[1].isDisk());
}
