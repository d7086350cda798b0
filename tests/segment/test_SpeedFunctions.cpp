#include "segment/SpeedFunctions.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(SpeedFunctions, SphereHasTotalCurvatureTwoOverRadius) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(20, 3.0));
    for (double k : totalCurvature(graph)) EXPECT_NEAR(k, 2.0 / 3.0, 0.01);
}

TEST(SpeedFunctions, CubeCurvatureLivesOnItsEdges) {
    const MeshGraph graph = MeshGraph::fromSoup(tessellatedCube(10, 1.0));
    const std::vector<double> kappa = totalCurvature(graph);
    double corner = 0, edge = 1e300, flatMax = 0;
    for (int v = 0; v < graph.vertexCount(); ++v) {
        const Vec3 p = graph.point(v);
        const int onFaces = (std::abs(std::abs(p.x) - 0.5) < 1e-12) +
                            (std::abs(std::abs(p.y) - 0.5) < 1e-12) +
                            (std::abs(std::abs(p.z) - 0.5) < 1e-12);
        if (onFaces == 1) flatMax = std::max(flatMax, kappa[std::size_t(v)]);
        if (onFaces == 2) edge = std::min(edge, kappa[std::size_t(v)]);
        if (onFaces == 3) corner = std::max(corner, kappa[std::size_t(v)]);
    }
    EXPECT_LT(flatMax, 1e-9);
    EXPECT_GT(edge, 5.0);  // ~1/(edge length) on a crease
    EXPECT_GT(corner, edge);
}

TEST(SpeedFunctions, RepulsiveAndAttractiveFollowEquationThree) {
    const MeshGraph graph = MeshGraph::fromSoup(tessellatedCube(6, 1.0));
    const std::vector<double> kappa = totalCurvature(graph);
    const double w = 0.3;
    const auto repulsive = curvatureSpeed(graph, SpeedKind::EdgeRepulsive, w);
    const auto attractive = curvatureSpeed(graph, SpeedKind::EdgeAttractive, w);
    const auto uniform = curvatureSpeed(graph, SpeedKind::Uniform, w);
    for (std::size_t v = 0; v < kappa.size(); ++v) {
        EXPECT_DOUBLE_EQ(repulsive[v], 1 + w * kappa[v]);
        EXPECT_DOUBLE_EQ(attractive[v], 1 / (1 + w * kappa[v]));
        EXPECT_EQ(uniform[v], 1.0);
    }
    EXPECT_NEAR(defaultCurvatureWeight(graph, 6), 1.0, 1e-12);
    const auto byDefault = curvatureSpeed(graph, SpeedKind::EdgeAttractive);
    EXPECT_DOUBLE_EQ(byDefault[0], 1 / (1 + defaultCurvatureWeight(graph) * kappa[0]));
}

TEST(SpeedFunctions, ScalarGradientOfALinearRamp) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(8, 8, 0.5));
    std::vector<double> ramp;
    for (const Vec3& p : graph.points()) ramp.push_back(3 * p.x - 4 * p.y);  // |∇I| = 5
    for (double s : scalarGradientSpeed(graph, ramp, 0.2)) EXPECT_NEAR(s, 1 / (1 + 0.2 * 5), 1e-12);
    EXPECT_THROW(scalarGradientSpeed(graph, {1.0}, 1), std::invalid_argument);
    EXPECT_THROW(scalarGradientSpeed(graph, ramp, -1), std::invalid_argument);
}

TEST(SpeedFunctions, NamesRoundTrip) {
    for (SpeedKind k : {SpeedKind::Uniform, SpeedKind::EdgeRepulsive, SpeedKind::EdgeAttractive})
        EXPECT_EQ(parseSpeedKind(toString(k)), k);
    EXPECT_THROW(parseSpeedKind("fast"), std::invalid_argument);
}
