#include "segment/SampleSurfaces.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "segment/MeshGraph.hpp"

using namespace dfrecon;

namespace {

double largestAngle(const MeshGraph& graph) {
    double largest = 0;
    for (const auto& tri : graph.triangles())
        for (int k = 0; k < 3; ++k) {
            const Vec3 c = graph.point(tri[std::size_t(k)]);
            const Vec3 a = graph.point(tri[std::size_t((k + 1) % 3)]) - c;
            const Vec3 b = graph.point(tri[std::size_t((k + 2) % 3)]) - c;
            largest = std::max(largest, std::acos(dot(a, b) / (length(a) * length(b))));
        }
    return largest * 180 / M_PI;
}

}  // namespace

TEST(SampleSurfaces, GeodesicSphereIsAClosedSphereOfAcuteTriangles) {
    for (int f : {1, 2, 5, 16}) {
        const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(f, 2.0));
        EXPECT_EQ(graph.vertexCount(), 10 * f * f + 2);
        EXPECT_EQ(graph.triangleCount(), 20 * f * f);
        EXPECT_EQ(graph.boundaryEdgeCount(), 0);
        for (const Vec3& p : graph.points()) EXPECT_NEAR(length(p), 2.0, 1e-12);
        EXPECT_LT(largestAngle(graph), 90.0);
        // Outward orientation: the signed volume is positive.
        double volume = 0;
        for (const auto& t : graph.triangles())
            volume += dot(graph.point(t[0]), cross(graph.point(t[1]), graph.point(t[2]))) / 6;
        EXPECT_GT(volume, 0);
    }
}

TEST(SampleSurfaces, TessellatedCubeIsClosedWithExactArea) {
    const MeshGraph graph = MeshGraph::fromSoup(tessellatedCube(5, 2.0));
    EXPECT_EQ(graph.vertexCount(), 6 * 25 + 2);
    EXPECT_EQ(graph.boundaryEdgeCount(), 0);
    EXPECT_NEAR(graph.totalArea(), 24.0, 1e-12);
    double volume = 0;
    for (const auto& t : graph.triangles())
        volume += dot(graph.point(t[0]), cross(graph.point(t[1]), graph.point(t[2]))) / 6;
    EXPECT_NEAR(volume, 8.0, 1e-12);
}

TEST(SampleSurfaces, StaggeredGridIsObtuseWhenFlat) {
    const MeshGraph flat = MeshGraph::fromSoup(staggeredGrid(10, 10, 1.0, 0.2));
    EXPECT_NEAR(largestAngle(flat), 2 * std::atan(2.5) * 180 / M_PI, 1e-9);
    EXPECT_NEAR(flat.totalArea(), 10 * 10 * 0.2 + 0.0, 1e-9);
    const MeshGraph equilateral = MeshGraph::fromSoup(staggeredGrid(6, 6, 1.0, std::sqrt(0.75)));
    EXPECT_NEAR(largestAngle(equilateral), 60.0, 1e-9);
}
