#include "segment/FarthestPointSampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(FarthestPointSampling, EachSampleIsTheFarthestFromThoseBefore) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(12));
    const UpdateStencils stencils(graph);
    const FastMarching marching(stencils);
    const FarthestPoints samples = farthestPointSampling(marching, 12, 7);
    ASSERT_EQ(samples.vertices.size(), 12u);
    // The first: farthest from the start vertex.
    const GeodesicField fromStart = marching.solve({{7, 0, 0}});
    EXPECT_DOUBLE_EQ(fromStart.time[std::size_t(samples.vertices[0])],
                     fromStart.time[std::size_t(farthestVertex(fromStart))]);
    for (std::size_t i = 1; i < samples.vertices.size(); ++i) {
        // An independent solve from samples 0..i-1: sample i is at its maximum.
        std::vector<GeodesicSource> before;
        for (std::size_t j = 0; j < i; ++j) before.push_back({samples.vertices[j], 0, int(j)});
        const GeodesicField field = marching.solve(before);
        const double farthest = field.time[std::size_t(farthestVertex(field))];
        EXPECT_NEAR(field.time[std::size_t(samples.vertices[i])], farthest, 1e-12) << i;
        EXPECT_NEAR(samples.coveringRadius[i - 1], farthest, 1e-12) << i;
        EXPECT_LE(samples.coveringRadius[i], samples.coveringRadius[i - 1]);
        // Every earlier sample is about that far away (separation; measured
        // from the new sample, and fast marching is symmetric only up to its
        // discretisation error, about 1 % here).
        const GeodesicField fromNew = marching.solve({{samples.vertices[i], 0, 0}});
        for (std::size_t j = 0; j < i; ++j)
            EXPECT_GE(fromNew.time[std::size_t(samples.vertices[j])],
                      0.98 * samples.coveringRadius[i - 1]);
    }
    // The kept field is the solve from all samples.
    std::vector<GeodesicSource> all;
    for (std::size_t j = 0; j < samples.vertices.size(); ++j)
        all.push_back({samples.vertices[j], 0, int(j)});
    const GeodesicField together = marching.solve(all);
    for (int v = 0; v < graph.vertexCount(); ++v) {
        EXPECT_NEAR(samples.field.time[std::size_t(v)], together.time[std::size_t(v)], 1e-12);
        EXPECT_EQ(samples.field.label[std::size_t(v)], together.label[std::size_t(v)]);
    }
}

TEST(FarthestPointSampling, OnASphereTheSecondIsAntipodalAndTheThirdOnTheirEquator) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(16));
    const UpdateStencils stencils(graph);
    const FarthestPoints samples = farthestPointSampling(FastMarching(stencils), 3);
    const Vec3 a = graph.point(samples.vertices[0]), b = graph.point(samples.vertices[1]);
    EXPECT_LT(dot(a, b), -0.99);
    EXPECT_LT(std::abs(dot(graph.point(samples.vertices[2]), a)), 0.05);
    EXPECT_NEAR(samples.coveringRadius[1], M_PI / 2, 0.02);
}

TEST(FarthestPointSampling, StopsWhenEveryVertexIsASample) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(1, 1, 1.0));
    const UpdateStencils stencils(graph);
    const FarthestPoints samples = farthestPointSampling(FastMarching(stencils), 10);
    EXPECT_EQ(samples.vertices.size(), 4u);
    EXPECT_THROW(farthestPointSampling(FastMarching(stencils), 0), std::invalid_argument);
    EXPECT_THROW(farthestPointSampling(FastMarching(stencils), 2, 9), std::invalid_argument);
}
