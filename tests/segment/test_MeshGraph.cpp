#include "segment/MeshGraph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(MeshGraph, NeighboursAreMutualAndShareTheEdge) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(3));
    EXPECT_EQ(graph.vertexCount(), 92);
    EXPECT_EQ(graph.boundaryEdgeCount(), 0);
    for (int t = 0; t < graph.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k) {
            const int other = graph.neighbour(t, k);
            ASSERT_GE(other, 0);
            const auto& tri = graph.triangle(t);
            const int u = tri[std::size_t((k + 1) % 3)], w = tri[std::size_t((k + 2) % 3)];
            EXPECT_GE(graph.cornerOf(other, u), 0);
            EXPECT_GE(graph.cornerOf(other, w), 0);
            EXPECT_LT(graph.cornerOf(other, tri[std::size_t(k)]), 0);
            const int back = 3 - graph.cornerOf(other, u) - graph.cornerOf(other, w);
            EXPECT_EQ(graph.neighbour(other, back), t);
        }
    for (int v = 0; v < graph.vertexCount(); ++v)
        for (int t : graph.trianglesAround(v)) EXPECT_GE(graph.cornerOf(t, v), 0);
}

TEST(MeshGraph, AreasAndEdgeLengthsOfAUnitCube) {
    const MeshGraph graph = MeshGraph::fromSoup(tessellatedCube(4, 1.0));
    EXPECT_NEAR(graph.totalArea(), 6.0, 1e-12);
    const std::vector<double> areas = graph.vertexAreas();
    EXPECT_NEAR(std::accumulate(areas.begin(), areas.end(), 0.0), 6.0, 1e-12);
    // Edges of 0.25: 48 on the cube's edges, 24 inside each face; 96 diagonals.
    const double expected =
        (12 * 4 * 0.25 + 6 * (2 * 4 * 3) * 0.25 + 6 * 16 * 0.25 * std::sqrt(2.0)) /
        (12 * 4 + 6 * 2 * 4 * 3 + 6 * 16);
    EXPECT_NEAR(graph.meanEdgeLength(), expected, 1e-12);
}

TEST(MeshGraph, OpenGridHasBoundaryEdges) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(3, 2, 1.0));
    EXPECT_EQ(graph.boundaryEdgeCount(), 2 * (3 + 2));
    EXPECT_NEAR(graph.totalArea(), 6.0, 1e-12);
}

TEST(MeshGraph, RejectsBrokenInput) {
    std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    EXPECT_THROW(MeshGraph(points, {{0, 1, 5}}), std::invalid_argument);
    EXPECT_THROW(MeshGraph(points, {{0, 1, 1}}), std::invalid_argument);
    // Three triangles on edge (0, 1): not a manifold.
    EXPECT_THROW(MeshGraph(points, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), std::invalid_argument);
    EXPECT_NO_THROW(MeshGraph(points, {{0, 1, 2}, {1, 0, 3}}));
}
