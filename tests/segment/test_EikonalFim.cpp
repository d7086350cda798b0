// The OpenCL fast iterative method against its C++ reference (the same
// iteration) and against fast marching (the same discrete equations).
#include "segment/EikonalFim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "io/mesh/MeshIO.hpp"
#include "segment/SpeedFunctions.hpp"
#include "tests/segment/SegmentTestMeshes.hpp"

using namespace dfrecon;

namespace {

struct Difference {
    double maxTime = 0;  // largest |Δt|
    int labels = 0;      // vertices whose labels differ
};

Difference compare(const GeodesicField& a, const GeodesicField& b) {
    Difference d;
    for (std::size_t v = 0; v < a.time.size(); ++v) {
        if (a.time[v] == kUnreached || b.time[v] == kUnreached) {
            d.maxTime = std::max(d.maxTime, a.time[v] == b.time[v] ? 0.0 : kUnreached);
        } else {
            d.maxTime = std::max(d.maxTime, std::abs(a.time[v] - b.time[v]));
        }
        d.labels += a.label[v] != b.label[v];
    }
    return d;
}

struct Case {
    std::string name;
    MeshGraph graph;
    std::vector<double> speed;
    std::vector<GeodesicSource> sources;
    double scale;  // a typical distance, for relative tolerances
};

std::vector<Case> cases() {
    std::vector<Case> all;
    {
        MeshGraph g = MeshGraph::fromSoup(geodesicSphere(24));
        std::vector<GeodesicSource> s{{0, 0, 0}, {2000, 0, 1}, {4321, 0.1, 2}};
        all.push_back({"sphere, three sources", std::move(g), {}, s, 1.0});
    }
    {
        MeshGraph g = MeshGraph::fromSoup(tessellatedCube(16));
        std::vector<double> speed = curvatureSpeed(g, SpeedKind::EdgeAttractive);
        all.push_back(
            {"cube, attractive speed", std::move(g), speed, {{5, 0, 0}, {700, 0, 1}}, 1.0});
    }
    {
        MeshGraph g = MeshGraph::fromSoup(jitteredGeodesicSphere(24, 0.35));
        all.push_back({"jittered sphere, one source", std::move(g), {}, {{0, 0, 0}}, 1.0});
    }
    {
        MeshGraph g = MeshGraph::fromSoup(staggeredGrid(30, 120, 1.0 / 30, 0.2 / 30));
        all.push_back({"obtuse grid, unfolded", std::move(g), {}, {{1500, 0, 0}}, 1.0});
    }
    return all;
}

}  // namespace

TEST(EikonalFim, ReferenceConvergesToFastMarching) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const UpdateStencils stencils(c.graph);
        const GeodesicField marched = FastMarching(stencils, c.speed).solve(c.sources);
        FimStats stats;
        const GeodesicField iterated =
            eikonalFimReference(stencils, c.sources, c.speed, {}, &stats);
        EXPECT_TRUE(stats.converged);
        // With one source the discrete equations have one solution, which
        // both reach: measured ≤ 2e-10 (the settling tolerance, 1e-9 of an
        // edge's crossing time, accumulated along paths).
        const GeodesicField single = FastMarching(stencils, c.speed).solve({c.sources[0]});
        const Difference one =
            compare(single, eikonalFimReference(stencils, {c.sources[0]}, c.speed));
        EXPECT_LT(one.maxTime, 1e-6 * c.scale);
        EXPECT_EQ(one.labels, 0);
        // With several, fronts of different labels do not combine, and near
        // cell borders a vertex's label and time depend on each other: the
        // equations may have more than one solution there, and FIM's Jacobi
        // order may settle on another one than fast marching's causal
        // order. Away from borders (the vertex and all it depends on in one
        // cell) they must agree as above.
        int border = 0, differing = 0;
        double interior = 0;
        for (int v = 0; v < c.graph.vertexCount(); ++v) {
            bool inside = true;
            for (int k = stencils.first()[std::size_t(v)]; k < stencils.first()[std::size_t(v) + 1];
                 ++k) {
                const UpdateStencil& s = stencils.stencils()[std::size_t(k)];
                for (int corner : {s.a, s.b})
                    inside &= marched.label[std::size_t(corner)] == marched.label[std::size_t(v)] &&
                              iterated.label[std::size_t(corner)] == marched.label[std::size_t(v)];
            }
            const double d = std::abs(marched.time[std::size_t(v)] - iterated.time[std::size_t(v)]);
            differing += d > 1e-6 * c.scale;
            if (inside)
                interior = std::max(interior, d);
            else
                ++border;
        }
        EXPECT_LT(differing, c.graph.vertexCount() / 20);
        std::cout << c.name << ": " << differing << " of " << c.graph.vertexCount()
                  << " vertices differ by > 1e-6; largest difference "
                  << compare(marched, iterated).maxTime << ", away from borders " << interior
                  << " (" << border << " border vertices)\n";
    }
}

TEST(EikonalFim, DeviceRunsTheReferenceIteration) {
    ocl::Runtime runtime;
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const UpdateStencils stencils(c.graph);
        FimStats hostStats, deviceStats;
        const GeodesicField host =
            eikonalFimReference(stencils, c.sources, c.speed, {}, &hostStats);
        EikonalFim fim(runtime, stencils, c.speed);
        const GeodesicField device = fim.solve(c.sources, &deviceStats);
        EXPECT_TRUE(deviceStats.converged);
        const Difference d = compare(host, device);
        if (deviceStats.doublePrecision) {
            // Same operations in the same order, no fused multiply-adds:
            // measured identical on PoCL; allow rounding of a different libm sqrt.
            EXPECT_EQ(deviceStats.iterations, hostStats.iterations);
            EXPECT_LT(d.maxTime, 1e-12 * c.scale);
            EXPECT_EQ(d.labels, 0);
        } else {
            EXPECT_LT(d.maxTime, 1e-4 * c.scale);
        }
        // A second solve on the same buffers gives the same answer.
        const Difference again = compare(device, fim.solve(c.sources));
        EXPECT_EQ(again.maxTime, 0.0);
    }
}

TEST(EikonalFim, AgreesWithFastMarchingOnAScannedMesh) {
    // libcgal-demo's bunny (make setup): irregular, 14K obtuse corners.
    const std::string path = std::string(DFRECON_FIXTURES) + "/meshes/bunny00.off";
    if (!std::ifstream(path)) GTEST_SKIP() << path << " missing (make setup)";
    const MeshGraph graph = MeshGraph::fromMesh(readMesh(path));
    const UpdateStencils stencils(graph);
    EXPECT_GT(stencils.obtuseCorners(), 1000);
    ocl::Runtime runtime;
    const GeodesicField marched = FastMarching(stencils).solve({{0, 0, 0}});
    const GeodesicField device = EikonalFim(runtime, stencils).solve({{0, 0, 0}});
    double largest = 0;
    for (double t : marched.time) largest = std::max(largest, t);
    // Measured: 5e-9 % of the bounding-box diagonal.
    EXPECT_LT(compare(marched, device).maxTime, 1e-8 * largest);
    EXPECT_EQ(compare(marched, device).labels, 0);
}

TEST(EikonalFim, UnreachedVerticesStayUnreachedOnTheDevice) {
    const int otherComponent = 16;  // twoComponents(): the second grid's first vertex
    const MeshGraph graph = MeshGraph::fromSoup(dfrecon::testing::twoComponents());
    const UpdateStencils stencils(graph);
    ocl::Runtime runtime;
    const GeodesicField device = EikonalFim(runtime, stencils).solve({{0, 0, 0}});
    const GeodesicField host = eikonalFimReference(stencils, {{0, 0, 0}});
    for (int v = otherComponent; v < graph.vertexCount(); ++v) {
        EXPECT_EQ(device.time[std::size_t(v)], kUnreached);
        EXPECT_EQ(device.label[std::size_t(v)], -1);
    }
    EXPECT_EQ(compare(device, host).maxTime, 0.0);
}

TEST(EikonalFim, RejectsBadSources) {
    const MeshGraph graph = MeshGraph::fromSoup(squareGrid(2, 2, 1.0));
    const UpdateStencils stencils(graph);
    EXPECT_THROW(eikonalFimReference(stencils, {{99, 0, 0}}), std::invalid_argument);
}
