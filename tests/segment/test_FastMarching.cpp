#include "segment/FastMarching.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/segment/SegmentTestMeshes.hpp"

using namespace dfrecon;
using dfrecon::testing::errorAgainst;
using dfrecon::testing::greatCircle;
using dfrecon::testing::nearestVertex;

namespace {

/// Fast-marching error against great-circle distances from vertex 0 on the
/// unit geodesic sphere of the given frequency, in % of the radius.
dfrecon::testing::ErrorStats sphereErrorPct(int frequency) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(frequency));
    const UpdateStencils stencils(graph);
    const GeodesicField field = FastMarching(stencils).solve({{0, 0.0, 0}});
    const Vec3 source = graph.point(0);
    auto e = errorAgainst(graph, field.time, [&](Vec3 p) { return greatCircle(source, p, 1.0); });
    e.mean *= 100;
    e.max *= 100;
    return e;
}

}  // namespace

TEST(FastMarching, SphereErrorBelowOnePercentAndShrinkingWithRefinement) {
    // 642, 10242, 40962 and 100002 vertices.
    double previous = 1e9;
    for (int frequency : {8, 32, 64, 100}) {
        const auto e = sphereErrorPct(frequency);
        SCOPED_TRACE("frequency " + std::to_string(frequency));
        EXPECT_LT(e.mean, previous);
        previous = e.mean;
        if (frequency == 100) {
            // Measured: mean 0.455 %, max 0.795 % of the radius.
            EXPECT_LT(e.mean, 1.0);
            EXPECT_LT(e.max, 1.5);
        }
    }
}

TEST(FastMarching, PlaneWaveIsExactOnAFlatGrid) {
    // Sources: the whole left and bottom border with the times of a plane
    // wave; the linear update reproduces a linear field exactly.
    for (const bool obtuse : {false, true}) {
        const MeshGraph graph = MeshGraph::fromSoup(obtuse ? staggeredGrid(30, 60, 1.0, 0.25)
                                                           : squareGrid(30, 30, 1.0));
        const UpdateStencils stencils(graph);
        const Vec3 direction{std::cos(0.4), std::sin(0.4), 0};
        std::vector<GeodesicSource> sources;
        for (int v = 0; v < graph.vertexCount(); ++v) {
            const Vec3 p = graph.point(v);
            if (p.x < 0.75 || p.y < 0.3) sources.push_back({v, dot(p, direction), 0});
        }
        const GeodesicField field = FastMarching(stencils).solve(sources);
        const auto e = errorAgainst(graph, field.time, [&](Vec3 p) { return dot(p, direction); });
        EXPECT_LT(e.max, 1e-9) << (obtuse ? "staggered" : "square");
    }
}

TEST(FastMarching, PointSourceOnAPlaneConvergesToEuclideanDistance) {
    double previous = 1e9;
    for (int n : {20, 40, 80}) {
        const MeshGraph graph = MeshGraph::fromSoup(squareGrid(n, n, 1.0 / n));
        const int source = nearestVertex(graph, {0.5, 0.5, 0});
        const GeodesicField field = FastMarching(UpdateStencils(graph)).solve({{source, 0.0, 0}});
        const Vec3 s = graph.point(source);
        const auto e = errorAgainst(graph, field.time, [&](Vec3 p) { return length(p - s); });
        EXPECT_LT(e.mean, previous);
        EXPECT_LT(e.max, 0.05);  // of a unit square
        previous = e.mean;
    }
}

TEST(FastMarching, UnfoldingObtuseTrianglesIsMuchMoreAccurate) {
    // Isosceles triangles with 136° apex angles; Euclidean distances from
    // the middle. Measured: mean error 0.0022 with unfolding, 0.085 without.
    const double dx = 1.0 / 80, dy = 0.2 * dx;
    const MeshGraph graph = MeshGraph::fromSoup(staggeredGrid(80, 400, dx, dy));
    const int source = nearestVertex(graph, {0.5, 0.4, 0});
    const Vec3 s = graph.point(source);
    const auto euclidean = [&](Vec3 p) { return length(p - s); };
    const UpdateStencils unfolded(graph);
    UnfoldOptions plain;
    plain.unfoldObtuse = false;
    const UpdateStencils obtuse(graph, plain);
    const auto with =
        errorAgainst(graph, FastMarching(unfolded).solve({{source, 0, 0}}).time, euclidean);
    const auto without =
        errorAgainst(graph, FastMarching(obtuse).solve({{source, 0, 0}}).time, euclidean);
    EXPECT_LT(with.mean, 0.005);
    EXPECT_GT(without.mean, 10 * with.mean);
    EXPECT_GT(without.max, 10 * with.max);
}

TEST(FastMarching, UnfoldingHelpsOnAnIrregularSphere) {
    // A sphere with jittered vertices: 7.5 % of the corners obtuse.
    // Measured (frequency 40): mean error 1.14 % of the radius with
    // unfolding, 1.36 % without (max 2.09 % and 2.40 %); at frequency 100
    // 0.46 % and 0.74 %.
    const MeshGraph graph = MeshGraph::fromSoup(jitteredGeodesicSphere(40, 0.35));
    const Vec3 s = graph.point(0);
    const auto exact = [&](Vec3 p) { return greatCircle(s, p, 1.0); };
    const UpdateStencils unfolded(graph);
    UnfoldOptions plain;
    plain.unfoldObtuse = false;
    const UpdateStencils obtuse(graph, plain);
    EXPECT_GT(unfolded.obtuseCorners(), 3 * graph.triangleCount() / 20);
    const auto with = errorAgainst(graph, FastMarching(unfolded).solve({{0, 0, 0}}).time, exact);
    const auto without = errorAgainst(graph, FastMarching(obtuse).solve({{0, 0, 0}}).time, exact);
    EXPECT_LT(with.mean, 0.9 * without.mean);
    EXPECT_LT(with.max, 0.95 * without.max);
}

TEST(FastMarching, LabelsAreTheNearestSource) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(40, 40, 0.025));
    const std::vector<Vec3> sites{{0.2, 0.3, 0}, {0.8, 0.25, 0}, {0.45, 0.8, 0}};
    std::vector<GeodesicSource> sources;
    for (int i = 0; i < 3; ++i)
        sources.push_back({nearestVertex(graph, sites[std::size_t(i)]), 0.0, i});
    const GeodesicField field = FastMarching(UpdateStencils(graph)).solve(sources);
    int wrong = 0;
    for (int v = 0; v < graph.vertexCount(); ++v) {
        std::vector<double> d;
        for (const auto& s : sources) d.push_back(length(graph.point(v) - graph.point(s.vertex)));
        const int nearest = int(std::min_element(d.begin(), d.end()) - d.begin());
        std::vector<double> sorted = d;
        std::sort(sorted.begin(), sorted.end());
        // Away from the bisectors (more than an edge), the label must be exact.
        if (sorted[1] - sorted[0] > 0.05) wrong += field.label[std::size_t(v)] != nearest;
    }
    EXPECT_EQ(wrong, 0);
}

TEST(FastMarching, CollidingFrontsDoNotCombine) {
    // Four sources on the equator: the poles are π/2 from all of them. A
    // triangle update combining corners of two fronts would let the point
    // where they collide run towards the poles at √2 times the speed.
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(24));
    std::vector<GeodesicSource> sources;
    int label = 0;
    for (Vec3 p : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}})
        sources.push_back({nearestVertex(graph, p), 0.0, label++});
    const GeodesicField field = FastMarching(UpdateStencils(graph)).solve(sources);
    for (Vec3 pole : {Vec3{0, 0, 1}, Vec3{0, 0, -1}}) {
        double nearest = 1e9;
        for (const auto& s : sources)
            nearest = std::min(nearest, greatCircle(graph.point(s.vertex), pole, 1.0));
        EXPECT_NEAR(field.time[std::size_t(nearestVertex(graph, pole))], nearest, 0.01 * nearest);
    }
}

TEST(FastMarching, MarchingOverAFieldMatchesSolvingAtOnce) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(20));
    const UpdateStencils stencils(graph);
    const FastMarching marching(stencils);
    const std::vector<GeodesicSource> sources{{0, 0, 0}, {1500, 0, 1}, {3000, 0, 2}};
    GeodesicField incremental = marching.solve({sources[0]});
    marching.march(incremental, {sources[1]});
    marching.march(incremental, {sources[2]});
    const GeodesicField together = marching.solve(sources);
    double worst = 0;
    int labels = 0;
    for (int v = 0; v < graph.vertexCount(); ++v) {
        worst = std::max(
            worst, std::abs(incremental.time[std::size_t(v)] - together.time[std::size_t(v)]));
        labels += incremental.label[std::size_t(v)] != together.label[std::size_t(v)];
    }
    EXPECT_LT(worst, 1e-12);
    EXPECT_EQ(labels, 0);
}

TEST(FastMarching, SpeedScalesTimesAndStopsWork) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(10));
    const UpdateStencils stencils(graph);
    const GeodesicField unit = FastMarching(stencils).solve({{0, 0, 0}});
    const GeodesicField fast =
        FastMarching(stencils, std::vector<double>(std::size_t(graph.vertexCount()), 4.0))
            .solve({{0, 0, 0}});
    for (int v = 0; v < graph.vertexCount(); ++v)
        EXPECT_NEAR(fast.time[std::size_t(v)], unit.time[std::size_t(v)] / 4, 1e-12);
    MarchOptions stop;
    stop.maxTime = 1.0;
    std::vector<int> order;
    stop.finalOrder = &order;
    const GeodesicField partial = FastMarching(stencils).solve({{0, 0, 0}}, stop);
    EXPECT_GT(order.size(), 10u);
    EXPECT_LT(order.size(), std::size_t(graph.vertexCount()));
    for (int v : order) EXPECT_LE(partial.time[std::size_t(v)], 1.0);
    for (std::size_t i = 1; i < order.size(); ++i)
        EXPECT_GE(partial.time[std::size_t(order[i])], partial.time[std::size_t(order[i - 1])]);
    EXPECT_THROW(FastMarching(stencils, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(FastMarching(stencils, std::vector<double>(std::size_t(graph.vertexCount()), 0.0)),
                 std::invalid_argument);
}

TEST(FastMarching, UnreachedComponentStaysUnreached) {
    const int otherComponent = 16;  // twoComponents(): the second grid's first vertex
    const MeshGraph graph = MeshGraph::fromSoup(dfrecon::testing::twoComponents());
    const GeodesicField field = FastMarching(UpdateStencils(graph)).solve({{0, 0, 0}});
    for (int v = otherComponent; v < graph.vertexCount(); ++v) {
        EXPECT_EQ(field.time[std::size_t(v)], kUnreached);
        EXPECT_EQ(field.label[std::size_t(v)], -1);
    }
    EXPECT_NEAR(field.time[15], std::hypot(3.0, 3.0), 1e-9);  // across the diagonal
    EXPECT_EQ(farthestVertex(field), 15);
}
